// remote.hpp - a call into a function that runs in the other program, and the
// answering of such calls (tools/grading/judge/README.md).
//
// The judge and the student's server are peers. Each serves the functions the
// other may call, by number (the index of the region in the reference), and
// calls the others through call<ID>(), which stands for a function's body:
//
//     return ::rt::judge::call<7>(&::rt::hit_sphere_textbook, s, r, tmin, tmax, rec);
//
// In the judge, stage N's bodies are such lines, and the server answers with
// the student's code. In the server, the bodies of the stages before N are,
// and the judge answers with the reference's: no reference body is compiled
// into the student's program. Stages after N are the kit's stubs.
//
// A parameter that is no data (an accelerator, a hit-item callable, a
// shape_hit_function) crosses as a handle: the peer gets a stand-in
// (remote_accelerator, remote_hit_item, remote_hit_shape) whose calls come
// back here, where the object itself answers. A template exercise is served
// as its instantiation for those stand-ins.
//
// Each program defines current_peer() once: judge.hpp (which starts the
// server at the first call) and server.cpp.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "arguments.hpp"
#include "link.hpp"
#include "wire.hpp"

namespace rt {
namespace judge {

class peer;

/// This program's peer (defined once in each program).
peer& current_peer();

#if __has_include(<rt/intersection/hit_list.hpp>)
template <class C, class = void>
struct has_closest_hit : std::false_type {};
template <class C>
struct has_closest_hit<C, std::void_t<decltype(std::declval<const C&>().closest_hit(
                              std::declval<const ray&>(), real(), real(), std::declval<hit_record&>()))>>
    : std::true_type {};
template <class C, class = void>
struct has_any_hit : std::false_type {};
template <class C>
struct has_any_hit<C, std::void_t<decltype(std::declval<const C&>().any_hit(std::declval<const ray&>(), real(),
                                                                             real()))>> : std::true_type {};

// --- the stand-ins for what crosses as a handle ---------------------------

/// The other side's accelerator.
struct remote_accelerator {
    endpoint* link = nullptr;
    std::uint32_t handle = 0;

    bool closest_hit(const ray& r, real tmin, real tmax, hit_record& rec) const
    {
        writer w;
        w.put(std::uint8_t(callback_method::closest_hit));
        w.put(r), w.put(tmin), w.put(tmax), w.put(rec);
        const std::string reply = link->call(callbacks + handle, w.bytes());
        reader in(reply);
        const bool hit = in.get<bool>();
        in.get(rec);
        return hit;
    }
    bool any_hit(const ray& r, real tmin, real tmax) const
    {
        writer w;
        w.put(std::uint8_t(callback_method::any_hit));
        w.put(r), w.put(tmin), w.put(tmax);
        const std::string reply = link->call(callbacks + handle, w.bytes());
        reader in(reply);
        return in.get<bool>();
    }
};

/// The other side's hit-item callable (closest_hit_groups).
struct remote_hit_item {
    endpoint* link = nullptr;
    std::uint32_t handle = 0;

    bool operator()(std::uint32_t item, const ray& r, real tmin, real tmax, hit_record& rec) const
    {
        writer w;
        w.put(std::uint8_t(callback_method::hit_item));
        w.put(item), w.put(r), w.put(tmin), w.put(tmax), w.put(rec);
        const std::string reply = link->call(callbacks + handle, w.bytes());
        reader in(reply);
        const bool hit = in.get<bool>();
        in.get(rec);
        return hit;
    }
};

/// A shape_hit_function is a plain function pointer: remote_hit_shape stands for
/// the other side's, and asks it with the handle of the call under way.
struct shape_hit_target {
    endpoint* link = nullptr;
    std::uint32_t handle = 0;
};

inline shape_hit_target& current_shape_hit()
{
    thread_local shape_hit_target target;
    return target;
}

inline bool remote_hit_shape(const shape& item, const ray& r, real tmin, real tmax, hit_record& rec)
{
    const shape_hit_target target = current_shape_hit();
    if (target.link == nullptr)
        throw std::runtime_error("remote_hit_shape called outside a call");
    writer w;
    w.put(std::uint8_t(callback_method::hit_shape));
    w.put(item), w.put(r), w.put(tmin), w.put(tmax), w.put(rec);
    const std::string reply = target.link->call(callbacks + target.handle, w.bytes());
    reader in(reply);
    const bool hit = in.get<bool>();
    in.get(rec);
    return hit;
}

#endif

// --- where a served call's parameters live ---------------------------------

/// What a parameter's holder needs besides the bytes: the link (for a callback's stand-in)
/// and the copy kept of this parameter from the function's last call (is_kept).
struct call_context {
    endpoint* link = nullptr;
    std::map<std::uint64_t, std::shared_ptr<void>>* kept = nullptr;
    std::uint32_t id = 0;
    std::size_t index = 0;

    std::shared_ptr<void>& kept_copy() const { return (*kept)[(std::uint64_t(id) << 8) | index]; }
};

#if __has_include(<rt/intersection/hit_list.hpp>)
template <>
struct never_kept<shading_options> : std::true_type {};   // it points at a generator the callee draws from
#endif

template <class P, class = void>
struct holder;

template <class P>
struct holder<P, std::enable_if_t<is_kept<P>>> {
    std::shared_ptr<bare<P>> value;
    void read(reader& in, const call_context& c)
    {
        std::shared_ptr<void>& kept = c.kept_copy();
        const auto mark = in.get<std::uint8_t>();
        if (mark == 1) {
            if (!kept)
                throw wire_error("a mark for a value that never came");
            value = std::static_pointer_cast<bare<P>>(kept);
        } else if (mark == 0) {
            auto fresh = std::make_shared<bare<P>>();
            in.get(*fresh);
            kept = fresh;
            value = std::move(fresh);
        } else {
            throw wire_error("a parameter mark that is neither 0 nor 1");
        }
    }
    P pass() { return *value; }
    void write(writer&) const {}
};


template <class P, class>
struct holder {
    bare<P> value{};
    void read(reader& in, const call_context&) { in.get(value); }
    P pass() { return static_cast<P>(value); }
    void write(writer& out) const
    {
        if constexpr (is_out<P>)
            out.put(value);
        else
            (void)out;
    }
};

template <class P>
struct holder<P, std::enable_if_t<is_pointer_in<P>::value>> {
    std::remove_cv_t<std::remove_pointer_t<bare<P>>> value{};
    bool null = true;
    void read(reader& in, const call_context&)
    {
        null = !in.get<bool>();
        if (!null)
            in.get(value);
    }
    bare<P> pass() { return null ? nullptr : &value; }
    void write(writer&) const {}
};

template <class P>
struct holder<P, std::enable_if_t<is_stream<P>>> {
    std::ostringstream value;
    void read(reader&, const call_context&) {}
    std::ostream& pass() { return value; }
    void write(writer& out) const { out.put(value.str()); }
};

#if __has_include(<rt/intersection/hit_list.hpp>)
template <class P>
struct holder<P, std::enable_if_t<std::is_same<bare<P>, statement>::value>> {
    statement value = blank_statement();
    void read(reader& in, const call_context&) { in.get(value); }
    P pass() { return static_cast<P>(value); }
    void write(writer& out) const
    {
        if constexpr (is_out<P>)
            out.put(value);
        else
            (void)out;
    }
};

template <class P>
struct holder<P, std::enable_if_t<std::is_same<bare<P>, shading_options>::value>> {
    shading_options value;
    pcg32 random;
    void read(reader& in, const call_context&)
    {
        in.get(value.light_falloff);
        value.random = in.get<bool>() ? &random : nullptr;
        if (value.random != nullptr)
            in.get(random);
    }
    P pass() { return static_cast<P>(value); }
    void write(writer& out) const
    {
        out.put(value.random != nullptr);
        if (value.random != nullptr)
            out.put(random);
    }
};

template <class P>
struct holder<P, std::enable_if_t<std::is_same<bare<P>, remote_accelerator>::value ||
                                  std::is_same<bare<P>, remote_hit_item>::value>> {
    bare<P> value;
    void read(reader& in, const call_context& c)
    {
        value.link = c.link;
        in.get(value.handle);
    }
    P pass() { return static_cast<P>(value); }
    void write(writer&) const {}
};

template <class P>
struct holder<P, std::enable_if_t<std::is_same<bare<P>, shape_hit_function>::value>> {
    std::uint32_t handle = own_hit_shape;
    endpoint* link = nullptr;
    void read(reader& in, const call_context& c)
    {
        in.get(handle);
        link = c.link;
    }
    shape_hit_function pass()
    {
        if (handle == own_hit_shape)
            return &hit_shape;
        current_shape_hit() = shape_hit_target{link, handle};
        return &remote_hit_shape;
    }
    void write(writer&) const {}
};

#endif

// --- the peer ----------------------------------------------------------------

class peer {
public:
    using connect_function = std::function<endpoint&()>;

    /// `connect` gives the link at the first call (the judge starts the server then).
    explicit peer(connect_function connect) : connect_(std::move(connect)) {}
    peer(const peer&) = delete;
    peer& operator=(const peer&) = delete;

    /// Serves `function` as number `id`.
    template <class R, class... P>
    void add(std::uint32_t id, R (*function)(P...))
    {
        if (functions_.size() <= id)
            functions_.resize(id + 1);
        functions_[id] = [this, function, id](reader& in, writer& out) {
            invoke(id, function, in, out, std::index_sequence_for<P...>{});
        };
    }

    /// Calls number `id` on the other side with these arguments, which match P.
    template <class R, class... P, class... A>
    R call(std::uint32_t id, A&... arguments)
    {
        return call_with<R, P...>(id, std::index_sequence_for<P...>{}, std::tie(arguments...));
    }

private:
    template <class R, class... P, std::size_t... I, class Tuple>
    R call_with(std::uint32_t id, std::index_sequence<I...>, Tuple arguments)
    {
        endpoint& to = link();
        const std::size_t mark = callbacks_.size();
        struct unregister {
            std::vector<std::function<void(reader&, writer&)>>& table;
            std::size_t mark;
            ~unregister() { table.resize(mark); }
        } guard{callbacks_, mark};
        writer w;
        (send<P>(w, std::get<I>(arguments), id, I), ...);
        const std::string reply = to.call(id, w.bytes());
        reader in(reply);
        if constexpr (std::is_void<R>::value) {
            (receive<P>(in, std::get<I>(arguments)), ...);
            finish(in);
        } else {
            R result{};
            in.get(result);
            (receive<P>(in, std::get<I>(arguments)), ...);
            finish(in);
            return result;
        }
    }

public:
    /// The link, connected (and its handler set) at the first use.
    endpoint& link()
    {
        endpoint& to = connect_();   // throws when the other side has ended
        if (&to != link_) {
            link_ = &to;
            link_->set_handler([this](std::uint32_t target, reader& in, writer& out) { answer(target, in, out); });
        }
        return to;
    }

private:
    void answer(std::uint32_t target, reader& in, writer& out)
    {
        if (target < callbacks) {
            if (target >= functions_.size() || !functions_[target])
                throw std::runtime_error("function " + std::to_string(target) + " is not served here");
            functions_[target](in, out);
            return;
        }
        if (target - callbacks >= callbacks_.size())
            throw std::runtime_error("a callback that was not passed in this call");
        // a copy: the callback may call the other side, whose callbacks are added to the table
        const auto callback = callbacks_[target - callbacks];
        callback(in, out);
    }

    static void finish(const reader& in)
    {
        if (!in.done())
            throw wire_error("a reply longer than the values it returns");
    }

    template <class R, class... P, std::size_t... I>
    void invoke(std::uint32_t id, R (*function)(P...), reader& in, writer& out, std::index_sequence<I...>)
    {
        std::tuple<holder<P>...> held;
        (std::get<I>(held).read(in, call_context{link_, &kept_, id, I}), ...);
        if (!in.done())
            throw wire_error("a call longer than its arguments");
#if __has_include(<rt/intersection/hit_list.hpp>)
        struct restore {
            shape_hit_target value;
            ~restore() { current_shape_hit() = value; }
        } guard{current_shape_hit()};
#endif
        if constexpr (std::is_void<R>::value) {
            function(std::get<I>(held).pass()...);
        } else {
            const R result = function(std::get<I>(held).pass()...);
            out.put(result);
        }
        (std::get<I>(held).write(out), ...);
    }

    template <class P, class A>
    void send(writer& w, A& argument, std::uint32_t id, std::size_t index)
    {
        if constexpr (is_stream<P>) {
            (void)w;
            (void)argument;
        } else if constexpr (is_kept<P>) {
            writer value;
            value.put(static_cast<const bare<P>&>(argument));
            const std::uint64_t key = (std::uint64_t(id) << 8) | index;
            auto last = sent_.find(key);
            if (last != sent_.end() && value.bytes().size() >= kept_from_bytes && last->second == value.bytes()) {
                w.put(std::uint8_t(1));
                return;
            }
            w.put(std::uint8_t(0));
            w.raw(value.bytes().data(), value.bytes().size());
            if (value.bytes().size() >= kept_from_bytes)
                sent_[key] = value.take();
            else if (last != sent_.end())
                sent_.erase(last);
        } else if constexpr (has_wire<bare<P>>::value) {
            w.put(static_cast<const bare<P>&>(argument));
        } else if constexpr (is_pointer_in<P>::value) {
            w.put(argument != nullptr);
            if (argument != nullptr)
                w.put(*argument);
        } else {
            (void)id;
            (void)index;
            w.put(enlist<bare<P>>(argument));
        }
    }

    template <class P, class A>
    static void receive(reader& in, A& argument)
    {
#if __has_include(<rt/intersection/hit_list.hpp>)
        if constexpr (std::is_same<bare<P>, shading_options>::value) {
            // the generator the options point at was drawn from: its state comes back
            const bool drew = in.get<bool>();
            if (drew != (argument.random != nullptr))
                throw wire_error("options that came back with a generator they did not have");
            if (drew)
                in.get(*argument.random);
            return;
        }
#endif
        if constexpr (is_out<P>) {
            if constexpr (is_stream<P>) {
                const auto text = in.get<std::string>();
                argument.write(text.data(), std::streamsize(text.size()));
            } else {
                in.get(argument);
            }
        } else {
            (void)in;
            (void)argument;
        }
    }

    static void expect(reader& in, callback_method method)
    {
        if (in.get<std::uint8_t>() != std::uint8_t(method))
            throw wire_error("a callback asked for a method it does not have");
    }

    /// A handle for a callback passed to the other side: its calls are answered here.
    template <class C, class A>
    std::uint32_t enlist(A& argument)
    {
#if __has_include(<rt/intersection/hit_list.hpp>)
        if constexpr (std::is_same<C, shape_hit_function>::value) {
            if (argument == &hit_shape)
                return own_hit_shape;
            const shape_hit_function f = argument;
            const shape_hit_target target = current_shape_hit();   // what f may stand for
            callbacks_.push_back([f, target](reader& in, writer& out) {
                expect(in, callback_method::hit_shape);
                shape item;
                ray r;
                real tmin = 0, tmax = 0;
                hit_record rec;
                in.get(item), in.get(r), in.get(tmin), in.get(tmax), in.get(rec);
                const shape_hit_target before = current_shape_hit();
                current_shape_hit() = target;
                bool hit = false;
                try {
                    hit = f(item, r, tmin, tmax, rec);
                } catch (...) {
                    current_shape_hit() = before;
                    throw;
                }
                current_shape_hit() = before;
                out.put(hit);
                out.put(rec);
            });
        } else if constexpr (has_closest_hit<C>::value || has_any_hit<C>::value) {
            const C* accel = &argument;
            callbacks_.push_back([accel](reader& in, writer& out) {
                const auto method = in.get<std::uint8_t>();
                ray r;
                real tmin = 0, tmax = 0;
                in.get(r), in.get(tmin), in.get(tmax);
                if (method == std::uint8_t(callback_method::closest_hit)) {
                    hit_record rec;
                    in.get(rec);
                    if constexpr (has_closest_hit<C>::value) {
                        out.put(bool(accel->closest_hit(r, tmin, tmax, rec)));
                        out.put(rec);
                        return;
                    }
                } else if (method == std::uint8_t(callback_method::any_hit)) {
                    if constexpr (has_any_hit<C>::value) {
                        out.put(bool(accel->any_hit(r, tmin, tmax)));
                        return;
                    }
                }
                throw std::runtime_error("the test's accelerator has no such method");
            });
        } else {
            static_assert(std::is_invocable_r<bool, A&, std::uint32_t, const ray&, real, real, hit_record&>::value,
                          "a parameter that cannot cross: not data, a stream, an accelerator, a hit function "
                          "or a hit-item callable");
            A* item = &argument;
            callbacks_.push_back([item](reader& in, writer& out) {
                expect(in, callback_method::hit_item);
                std::uint32_t index = 0;
                ray r;
                real tmin = 0, tmax = 0;
                hit_record rec;
                in.get(index), in.get(r), in.get(tmin), in.get(tmax), in.get(rec);
                out.put(bool((*item)(index, r, tmin, tmax, rec)));
                out.put(rec);
            });
        }
#else
        static_assert(sizeof(C*) == 0, "a parameter that cannot cross: this reference has no callbacks");
        (void)argument;
#endif
        return std::uint32_t(callbacks_.size() - 1);
    }

    connect_function connect_;
    endpoint* link_ = nullptr;
    std::vector<std::function<void(reader&, writer&)>> functions_;
    std::vector<std::function<void(reader&, writer&)>> callbacks_;
    std::map<std::uint64_t, std::string> sent_;                  // the last bytes of each kept parameter
    std::map<std::uint64_t, std::shared_ptr<void>> kept_;       // the copies kept of what came
};

/// A function whose body runs in the other program (front.hpp declares it).
template <unsigned ID, class R, class... P, class... A>
R call(R (*)(P...), A&&... arguments)
{
    static_assert(sizeof...(P) == sizeof...(A), "call<ID>(&f, ...) passes each of f's parameters");
    try {
        return current_peer().call<R, P...>(ID, arguments...);
    } catch (const wire_error& e) {
        throw link_error(std::string("the other program's reply did not decode: ") + e.what());
    }
}

} // namespace judge
} // namespace rt
