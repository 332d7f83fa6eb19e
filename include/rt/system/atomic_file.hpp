// atomic_file.hpp - write a file completely or not at all.
//
// Every output rt writes goes to a temporary file in the same folder first and
// is renamed over the target only when it is complete and on the disk. A
// rename within one folder is atomic on POSIX file systems (rename(2), IEEE Std
// 1003.1-2017), so a reader sees either the old file or the new one, and a
// failure (a full disk, a crash, an exception while encoding) leaves the
// previous file untouched. On Windows the rename is MoveFileExW (platform.hpp
// says which guarantees Microsoft documents; docs/reliability.md what that
// means for a write there).
//
// What is promised (docs/reliability.md):
//  - no temporary file is left behind: on an exception, on a write error, and
//    when the program is stopped by SIGINT, SIGTERM or SIGHUP (a handler removes
//    the temporary files being written, then dies of the signal as it would
//    have) or on Windows by Ctrl+C, Ctrl+Break or its console closing;
//  - the file size limit (ulimit -f) is a write error with a message, not a
//    death by SIGXFSZ: the writing thread blocks that signal while it writes,
//    and the process's signal actions are as they were after it;
//  - the new file's bytes are on the disk (fsync, FlushFileBuffers) before
//    the rename, so a power cut leaves the old file or the complete new one;
//  - write_all_atomically writes several files all or none: every temporary
//    file is complete before the first rename.
// The POSIX handlers are installed by each write, and only over the default
// action: a program that handles or ignores these signals itself keeps its way,
// and rt::set_interrupt_cleanup(false) turns them off (then an interrupted write
// leaves its temporary file, "<name>.tmp-<16 hex digits>", behind).
#pragma once

#include <cstddef>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <streambuf>
#include <string>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "os_error.hpp"
#include "path_text.hpp"
#include "platform.hpp"
#include "temporary_file.hpp"

namespace rt {

namespace detail {

/// A std::streambuf writing to a new_file that keeps the error of the first
/// failed write, so the message can say why (ENOSPC, EFBIG, EIO).
class file_buffer : public std::streambuf {
public:
    explicit file_buffer(new_file& file) : file_(file), buffer_(std::size_t(1) << 16)
    {
        setp(buffer_.data(), buffer_.data() + buffer_.size());
    }
    int failure() const { return failure_; }

protected:
    int_type overflow(int_type c) override
    {
        if (!drain())
            return traits_type::eof();
        if (!traits_type::eq_int_type(c, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(c);
            pbump(1);
        }
        return traits_type::not_eof(c);
    }
    int sync() override { return drain() ? 0 : -1; }
    std::streamsize xsputn(const char* data, std::streamsize count) override
    {
        if (count < epptr() - pptr()) {
            std::memcpy(pptr(), data, std::size_t(count));
            pbump(int(count));
            return count;
        }
        if (!drain() || !write_all(data, std::size_t(count)))
            return 0;
        return count;
    }

private:
    bool drain()
    {
        const std::size_t pending = std::size_t(pptr() - pbase());
        const bool ok = write_all(pbase(), pending);
        setp(buffer_.data(), buffer_.data() + buffer_.size());
        return ok;
    }
    bool write_all(const char* data, std::size_t count)
    {
        if (failure_ == 0 && count > 0)
            failure_ = file_.write(data, count);
        return failure_ == 0;
    }

    new_file& file_;
    std::vector<char> buffer_;
    int failure_ = 0;
};

/// One output being written: its target and its registered temporary file.
class pending_file {
public:
    explicit pending_file(const std::filesystem::path& target)
        : target_(target), temporary_(temporary_sibling(target))
    {
    }

    /// Creates the temporary file, fills it with `write` and puts it on the
    /// disk; throws rt::error with the reason (errno) when a byte could not be
    /// written.
    void fill(const std::function<void(std::ostream&)>& write)
    {
        new_file file; // closed before the temporary file is removed, on every path out
        const int code = file.create(temporary_.path());
        if (code != 0)
            throw error(source_location{utf8_text(target_)},
                        "expected to create a temporary file beside it, found that impossible (" + reason_of(code) +
                            "); choose another output path");
        temporary_.created();
        int failure = 0;
        {
            file_buffer buffer(file);
            std::ostream out(&buffer);
            write(out);
            out.flush();
            failure = buffer.failure();
            if (failure == 0 && !out)
                failure = EIO;
        }
        if (failure == 0)
            failure = file.sync();
        const int closed = file.close(); // NFS reports a full disk at close
        if (failure == 0)
            failure = closed;
        if (failure != 0)
            throw error(source_location{utf8_text(target_)},
                        "expected to write the file, found a write error (" + reason_of(failure) +
                            "); nothing was written, the previous file, if any, is unchanged");
    }

    /// Renames the temporary file over the target; throws rt::error on failure.
    void commit()
    {
        const int code = replace_file(temporary_.path(), target_);
        if (code != 0)
            throw error(source_location{utf8_text(target_)},
                        "expected to replace the file, found that impossible (" + reason_of(code) + ")");
        temporary_.release();
    }

    const std::filesystem::path& target() const { return target_; }

private:
    std::filesystem::path target_;
    registered_temporary temporary_;
};

} // namespace detail

/// Throws rt::error, with the reason, unless a file can be created at `target`:
/// its name fits the file system, its folder exists, is a folder and is
/// writable, and `target` is not a folder. Call it before a long render, so a
/// bad output path fails at once instead of at the end.
inline void check_writable(const std::filesystem::path& target)
{
    const source_location at{detail::utf8_text(target)};
    const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
    const std::string shown_folder = "'" + detail::shown_path(detail::utf8_text(folder)) + "'";
    const detail::file_status folder_status = detail::status_of(folder);
    if (folder_status.error == ENOENT)
        throw error(at, "expected an existing output folder, found none at " + shown_folder + "; create it first");
    if (folder_status.error != 0)
        throw error(at, "expected an existing output folder, found " + shown_folder + " cannot be reached (" +
                            detail::reason_of(folder_status.error) + "); choose another output path");
    if (!folder_status.folder)
        throw error(at, "expected an output folder, found " + shown_folder + " is a file; choose another output path");
    const std::size_t name_length = detail::path_length(target.filename());
    const std::size_t longest = detail::name_max(folder);
    if (name_length > longest)
        throw error(at, "expected a file name of at most " + std::to_string(longest) + " " + detail::length_unit +
                            ", found one of " + std::to_string(name_length) + "; choose a shorter name");
    if (detail::status_of(target).folder)
        throw error(at, "expected an output file, found a folder; give a file name such as out.png");
    detail::registered_temporary probe(detail::temporary_sibling(target));
    detail::new_file probe_file;
    const int code = probe_file.create(probe.path());
    if (code != 0)
        throw error(at, "expected a writable output folder, found " + shown_folder + " not writable (" +
                            detail::reason_of(code) + "); choose another output path");
    probe.created();
}

/// Throws rt::error when `target` is the same file as one of `inputs`, however
/// either path is spelled (device and inode, std::filesystem::equivalent: a
/// symbolic link or a hard link is caught), so that writing an output can never
/// destroy what a program read. Call it with check_writable, before any work.
inline void check_not_input(const std::filesystem::path& target, const std::vector<std::filesystem::path>& inputs)
{
    std::error_code ec;
    if (!std::filesystem::exists(target, ec))
        return; // a new file cannot be one of the inputs, which exist
    for (const std::filesystem::path& input : inputs)
        if (std::filesystem::equivalent(target, input, ec))
            throw error(source_location{detail::utf8_text(target)},
                        "expected an output path different from the input '" + detail::shown_path(detail::utf8_text(input)) +
                            "', found the same file; writing it would destroy the input, so choose another -o");
}

/// check_not_input for each of `targets`.
inline void check_not_input(const std::vector<std::filesystem::path>& targets,
                            const std::vector<std::filesystem::path>& inputs)
{
    for (const std::filesystem::path& target : targets)
        check_not_input(target, inputs);
}

/// Whether a write installs rt's interrupt cleanup (default: yes). On POSIX, the
/// first write of a program that left SIGINT, SIGTERM and SIGHUP at their
/// default action installs a handler that removes the temporary files being
/// written and then ends the process as the signal would have; on Windows, a
/// console handler that removes them. Call set_interrupt_cleanup(false) before
/// the first write in a program that wants its signals untouched (a handler it
/// installs itself is never replaced either way); an interrupted write then
/// leaves its temporary file behind.
inline void set_interrupt_cleanup(bool enabled)
{
    detail::temporary_files.cleanup_off.store(enabled ? 0 : 1);
}

/// Writes `target` atomically: `write(std::ostream&)` fills a temporary file,
/// which replaces `target` only if everything succeeded. Throws rt::error.
template <class Writer>
void write_atomically(const std::filesystem::path& target, Writer&& write)
{
    check_writable(target);
    detail::install_cleanup_handlers();
    detail::pending_file file(target);
    file.fill([&](std::ostream& out) { write(out); });
    file.commit();
}

/// One file of write_all_atomically: where, and what writes its bytes.
struct output_file {
    std::filesystem::path target;
    std::function<void(std::ostream&)> write;
};

/// Writes every file or none of them: all the temporary files are written
/// first, and only when every one is complete are they renamed over their
/// targets. A failure while writing (a full disk, the file size limit, an
/// exception, a signal) leaves every target as it was and no temporary file.
/// A rename can only fail if the folder changes under the program; then the
/// targets renamed so far that did not exist before are removed again, and the
/// message names any earlier one it had already replaced.
inline void write_all_atomically(const std::vector<output_file>& outputs)
{
    for (const output_file& output : outputs)
        check_writable(output.target);
    detail::install_cleanup_handlers();
    std::vector<std::unique_ptr<detail::pending_file>> files;
    for (const output_file& output : outputs) {
        files.push_back(std::make_unique<detail::pending_file>(output.target));
        files.back()->fill(output.write);
    }
    std::vector<bool> existed;
    for (const output_file& output : outputs)
        existed.push_back(detail::entry_exists(output.target));
    for (std::size_t k = 0; k < files.size(); ++k) {
        try {
            files[k]->commit();
        } catch (const error& e) {
            std::string replaced;
            for (std::size_t j = 0; j < k; ++j) {
                if (!existed[j])
                    detail::remove_file(files[j]->target());
                else
                    replaced += (replaced.empty() ? "" : ", ") + detail::shown_path(detail::utf8_text(files[j]->target()));
            }
            throw error(std::string(e.what()) + (replaced.empty() ? "; no other output was written"
                                                                  : "; already replaced: " + replaced));
        }
    }
}

} // namespace rt
