// link.hpp - the messages between the judge and the student's server
// (tools/grading/judge/README.md).
//
// Either side may call the other: the judge calls a student's function, and
// while it runs the server may call back into the judge (an accelerator or a
// callback the test passed), which may call the server again. So both sides
// wait the same way: send a call, then answer the calls that arrive until the
// reply to their own comes.
//
//     frame   = u32 size, then `size` bytes: u8 kind, payload
//     call    = kind 1: u32 target, the arguments
//     reply   = kind 2: the return value, then each out-parameter
//     thrown  = kind 3: u8 which (0 rt::error, 1 rt::exercise_not_done, 2 another
//               std::exception, 3 anything else), the message; for an rt::error
//               then the place it names (file, line, column)
//
// A frame is at most max_frame bytes; a size beyond it, a kind that is none of
// these, or a reply that does not decode is the server's fault, never the
// judge's crash (link_error).
#pragma once

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <poll.h>
#include <unistd.h>

#include <rt/core/error.hpp>

#include "wire.hpp"

namespace rt {
namespace judge {

/// The other side broke the protocol, stopped answering or ended.
class link_error : public std::runtime_error {
public:
    explicit link_error(const std::string& what) : std::runtime_error(what) {}
};

enum class frame_kind : std::uint8_t { call = 1, reply = 2, thrown = 3 };
enum class thrown_kind : std::uint8_t { rt_error = 0, not_done = 1, std_exception = 2, other = 3 };

constexpr std::uint32_t max_frame = 256u * 1024u * 1024u;

class endpoint {
public:
    /// Serves one incoming call: reads the arguments from `in`, writes the reply to `out`;
    /// what it throws goes back as a thrown frame.
    using handler = std::function<void(std::uint32_t target, reader& in, writer& out)>;

    endpoint(int in, int out) : in_(in), out_(out) {}

    void set_handler(handler h) { handler_ = std::move(h); }
    /// Seconds to wait for the other side's next frame (0: for ever); then link_error.
    void set_patience(double seconds) { patience_ = seconds; }
    /// Called when the other side is gone (end of file, a write that fails), to say why.
    void set_lost(std::function<std::string()> why) { lost_ = std::move(why); }

    /// Calls `target` on the other side and returns its reply's payload; rethrows what it threw.
    std::string call(std::uint32_t target, const std::string& arguments)
    {
        writer w;
        w.put(target);
        w.raw(arguments.data(), arguments.size());
        send(frame_kind::call, w.bytes());
        for (;;) {
            frame_kind kind{};
            std::string payload;
            receive(kind, payload);
            if (kind == frame_kind::reply)
                return payload;
            if (kind == frame_kind::thrown)
                rethrow(payload);
            answer(payload);
        }
    }

    /// Answers calls until the other side closes the link (the server's loop).
    void serve()
    {
        for (;;) {
            frame_kind kind{};
            std::string payload;
            if (!receive(kind, payload, true))
                return;
            if (kind != frame_kind::call)
                throw link_error("expected a call, found a reply with none pending");
            answer(payload);
        }
    }

private:
    void answer(const std::string& payload)
    {
        reader in(payload);
        const auto target = in.get<std::uint32_t>();
        writer out;
        frame_kind kind = frame_kind::reply;
        writer thrown;
        try {
            if (!handler_)
                throw link_error("no calls are served here");
            handler_(target, in, out);
        } catch (const link_error&) {
            throw;   // the link itself is broken: nothing can be answered
        } catch (const exercise_not_done& e) {
            kind = frame_kind::thrown;
            thrown.put(std::uint8_t(thrown_kind::not_done));
            thrown.put(std::string(e.what()));
        } catch (const error& e) {
            kind = frame_kind::thrown;
            thrown.put(std::uint8_t(thrown_kind::rt_error));
            thrown.put(std::string(e.what()));
            thrown.put(e.where().file);
            thrown.put(std::int32_t(e.where().line));
            thrown.put(std::int32_t(e.where().column));
        } catch (const std::exception& e) {
            kind = frame_kind::thrown;
            thrown.put(std::uint8_t(thrown_kind::std_exception));
            thrown.put(std::string(e.what()));
        } catch (...) {
            kind = frame_kind::thrown;
            thrown.put(std::uint8_t(thrown_kind::other));
            thrown.put(std::string("an exception that is not a std::exception"));
        }
        send(kind, kind == frame_kind::reply ? out.bytes() : thrown.bytes());
    }

    [[noreturn]] static void rethrow(const std::string& payload)
    {
        reader in(payload);
        const auto which = in.get<std::uint8_t>();
        const auto what = in.get<std::string>();
        switch (which) {
        case std::uint8_t(thrown_kind::rt_error): {
            source_location where;
            in.get(where.file);
            where.line = in.get<std::int32_t>();
            where.column = in.get<std::int32_t>();
            const std::string prefix = to_string(where) + ": ";
            if (where.line > 0 && what.compare(0, prefix.size(), prefix) == 0)
                throw error(where, what.substr(prefix.size()));
            throw error(what);
        }
        case std::uint8_t(thrown_kind::not_done): throw exercise_not_done(what);
        case std::uint8_t(thrown_kind::std_exception): throw std::runtime_error(what);
        case std::uint8_t(thrown_kind::other): throw std::runtime_error(what);
        default: throw link_error("a thrown frame of no known kind");
        }
    }

    /// The link is gone: why, in the words of lost_ (how the other program ended), with
    /// the link's own detail only when it adds something (a wait that ran out).
    [[noreturn]] void lost(const std::string& what) const
    {
        const std::string why = lost_ ? lost_() : std::string();
        if (why.empty())
            throw link_error(what);
        throw link_error(what.rfind("no answer", 0) == 0 ? why + " (" + what + ")" : why);
    }

    void send(frame_kind kind, const std::string& payload)
    {
        if (payload.size() + 1 > max_frame)
            throw link_error("a frame larger than " + std::to_string(max_frame) + " bytes");
        std::string frame(5, '\0');
        const auto size = std::uint32_t(payload.size() + 1);
        std::memcpy(&frame[0], &size, 4);
        frame[4] = char(kind);
        frame += payload;
        const char* at = frame.data();
        std::size_t left = frame.size();
        while (left > 0) {
            const ssize_t n = ::write(out_, at, left);
            if (n < 0 && errno == EINTR)
                continue;
            if (n <= 0)
                lost("the other side stopped reading");
            at += n;
            left -= std::size_t(n);
        }
    }

    /// False only at a clean end of file before a frame, when `end_ok`.
    bool receive(frame_kind& kind, std::string& payload, bool end_ok = false)
    {
        char head[5];
        if (!read_all(head, 5, end_ok))
            return false;
        std::uint32_t size = 0;
        std::memcpy(&size, head, 4);
        if (size < 1 || size > max_frame)
            lost("a frame of " + std::to_string(size) + " bytes");
        kind = frame_kind(std::uint8_t(head[4]));
        if (kind != frame_kind::call && kind != frame_kind::reply && kind != frame_kind::thrown)
            lost("a frame of no known kind");
        payload.resize(size - 1);
        if (size > 1)
            read_all(&payload[0], size - 1, false);
        return true;
    }

    /// Fills at[0, left) from what an earlier read left over, then from the pipe. A small
    /// request reads up to a chunk, so a frame's head and payload come in one system call
    /// (a test may make 200,000 calls). The chunk is allocated once: clearing 64 KiB on
    /// every read cost as much as the read.
    bool read_all(char* at, std::size_t left, bool end_ok)
    {
        bool first = true;
        if (inbox_at_ < inbox_end_) {
            const std::size_t n = std::min(left, inbox_end_ - inbox_at_);
            std::memcpy(at, inbox_.get() + inbox_at_, n);
            inbox_at_ += n;
            at += n;
            left -= n;
            first = false;
        }
        const auto start = std::chrono::steady_clock::now();
        while (left > 0) {
            if (patience_ > 0) {
                const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                const double wait = patience_ - spent;
                if (wait <= 0)
                    lost("no answer within " + std::to_string(int(patience_)) + " s");
                pollfd p{in_, POLLIN, 0};
                const int ready = ::poll(&p, 1, int(wait * 1000) + 1);
                if (ready < 0 && errno == EINTR)
                    continue;
                if (ready == 0)
                    continue;
            }
            const bool small = left < chunk;
            if (small && !inbox_)
                inbox_.reset(new char[chunk]);
            const ssize_t n = ::read(in_, small ? inbox_.get() : at, small ? chunk : left);
            if (n < 0 && errno == EINTR)
                continue;
            if (n == 0 && first && end_ok)
                return false;
            if (n <= 0)
                lost("the other side ended");
            first = false;
            std::size_t got = std::size_t(n);
            if (small) {
                const std::size_t used = std::min(got, left);
                std::memcpy(at, inbox_.get(), used);
                inbox_at_ = used;
                inbox_end_ = got;
                got = used;
            }
            at += got;
            left -= got;
        }
        return true;
    }

    static constexpr std::size_t chunk = 65536;
    std::unique_ptr<char[]> inbox_;  // bytes read past the frame being read: [inbox_at_, inbox_end_)
    std::size_t inbox_at_ = 0;
    std::size_t inbox_end_ = 0;

    int in_;
    int out_;
    double patience_ = 0;
    handler handler_;
    std::function<std::string()> lost_;
};

} // namespace judge
} // namespace rt
