// judge.hpp - the judge's side of a call into a student's function
// (tools/grading/judge/README.md).
//
// A judge is a stage's test suite built against headers in which each of the
// stage's exercise bodies is a call<ID>() (remote.hpp), and the unit that
// includes this header (judge_table.cpp, written by tools/grading/judge.py).
// So the judge holds the tests, the expected values and the reference of every
// other stage, and no line of the student's: call() sends the arguments to the
// student's server (a separate program, confined: confine.hpp), waits for the
// return value and the out-parameters, and hands them to the test, which
// judges them here. What the server does cannot reach the judge's memory, its
// output or its exit status; a server that crashes, hangs, ends or answers in
// bytes that do not decode fails the call, and so the case, with a message
// that says which.
//
// The server is started at the first call of a case and ended with the judge.
// The judge reads from its environment (tools/grading/judge.py sets it):
//     RT_JUDGE_SERVER      the server program
//     RT_JUDGE_SECONDS     how long it may take to answer one frame (the case's time)
//     RT_JUDGE_MEMORY_MB   its address space
//     RT_JUDGE_UID/_GID    who it runs as, when the judge is root
//     RT_JUDGE_STAGE       the stage it serves (its first argument), for a server of several
//     RT_JUDGE_CPU         the processor the judge and its server share, when set
#pragma once

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <fcntl.h>
#include <grp.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "confine.hpp"
#include "remote.hpp"

void rt_judge_table(::rt::judge::peer& judge);   // the functions the judge serves (judge_table.cpp)

namespace rt {
namespace judge {

inline long environment_number(const char* name, long otherwise)
{
    const char* text = std::getenv(name);
    if (text == nullptr || *text == '\0')
        return otherwise;
    char* end = nullptr;
    const long value = std::strtol(text, &end, 10);
    return *end == '\0' ? value : otherwise;
}

/// The student's server: started at the first call, ended with the judge.
class server_process {
public:
    server_process() = default;
    server_process(const server_process&) = delete;
    server_process& operator=(const server_process&) = delete;
    ~server_process() { stop(); }

    endpoint& link()
    {
        if (!broken_.empty())
            throw link_error("your code's program ended earlier in this case: " + broken_);
        if (!link_)
            start();
        return *link_;
    }

private:
    void start()
    {
        const char* server = std::getenv("RT_JUDGE_SERVER");
        if (server == nullptr || *server == '\0')
            throw link_error("RT_JUDGE_SERVER is not set: a judge runs under tools/grade.py only");
        std::signal(SIGPIPE, SIG_IGN);   // a server that ended makes a write fail, not the judge end
        const long seconds = environment_number("RT_JUDGE_SECONDS", 60);
        const long memory_mb = environment_number("RT_JUDGE_MEMORY_MB", 0);
        const long uid = environment_number("RT_JUDGE_UID", -1);
        const long gid = environment_number("RT_JUDGE_GID", -1);
        const std::string stage = std::to_string(environment_number("RT_JUDGE_STAGE", 0));
        // The judge waits while the server computes and the other way round: on one
        // processor each handover is a switch of task, on two it is a wake-up across
        // processors, which costs a virtual machine several times as much.
        const long cpu = environment_number("RT_JUDGE_CPU", -1);
        if (cpu >= 0 && cpu < CPU_SETSIZE) {
            cpu_set_t one;
            CPU_ZERO(&one);
            CPU_SET(int(cpu), &one);
            (void)::sched_setaffinity(0, sizeof one, &one);   // a hint: without it the case still runs
        }
        const std::vector<sock_filter> program = filter_program(true);
        int calls[2], replies[2];
        if (::pipe2(calls, O_CLOEXEC) != 0 || ::pipe2(replies, O_CLOEXEC) != 0)
            throw link_error(std::string("no pipe for the server: ") + std::strerror(errno));
        const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
        const pid_t parent = ::getpid();
        const pid_t child = ::fork();
        if (child < 0)
            throw link_error(std::string("the server could not be started: ") + std::strerror(errno));
        if (child == 0) {
            // from here to execve: system calls only, nothing that allocates
            const int in = ::fcntl(calls[0], F_DUPFD, 10);
            const int out = ::fcntl(replies[1], F_DUPFD, 10);
            if (in < 0 || out < 0 || null < 0 || ::dup2(in, call_fd) < 0 || ::dup2(out, reply_fd) < 0 ||
                ::dup2(null, 0) < 0 || ::dup2(null, 1) < 0 || ::dup2(null, 2) < 0)
                ::_exit(120);
            const long most = ::sysconf(_SC_OPEN_MAX);
            for (int fd = reply_fd + 1; fd < (most > 0 && most < 65536 ? most : 65536); ++fd)
                ::close(fd);
            limit(RLIMIT_CORE, 0);
            limit(RLIMIT_FSIZE, 0);
            limit(RLIMIT_NOFILE, reply_fd + 1);
            limit(RLIMIT_CPU, rlim_t(seconds > 0 ? seconds + 1 : 3600));
            if (memory_mb > 0)
                limit(RLIMIT_AS, rlim_t(memory_mb) * 1024 * 1024);
            if (gid >= 0 && (::setgroups(0, nullptr) != 0 || ::setresgid(gid_t(gid), gid_t(gid), gid_t(gid)) != 0))
                ::_exit(121);
            if (uid >= 0 && (::setresuid(uid_t(uid), uid_t(uid), uid_t(uid)) != 0 || ::getuid() != uid_t(uid)))
                ::_exit(121);
            if (::prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0) != 0 || ::getppid() != parent)
                ::_exit(122);
            if (!install_filter(program))
                ::_exit(123);
            char* const argv[] = {const_cast<char*>(server), const_cast<char*>(stage.c_str()), nullptr};
            char* const envp[] = {const_cast<char*>("LANG=C"), nullptr};
            ::execve(server, argv, envp);
            ::_exit(124);
        }
        if (null >= 0)
            ::close(null);
        ::close(calls[0]);
        ::close(replies[1]);
        pid_ = child;
        to_ = calls[1];
        from_ = replies[0];
        link_.reset(new endpoint(from_, to_));
        link_->set_patience(double(seconds > 0 ? seconds : 0));
        link_->set_lost([this] { return ended(); });
    }

    static void limit(int resource, rlim_t value)
    {
        const rlimit l{value, value};
        ::setrlimit(resource, &l);
    }

    /// How the server ended (it has, or is about to: its end of the link closed).
    std::string ended()
    {
        if (pid_ <= 0)
            return broken_;
        int status = 0;
        pid_t got = 0;
        for (int k = 0; k < 200 && (got = ::waitpid(pid_, &status, WNOHANG)) == 0; ++k)
            ::usleep(10000);
        std::string why;
        if (got != pid_) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, &status, 0);
            why = "it stopped answering and was ended";
        } else if (WIFEXITED(status)) {
            switch (WEXITSTATUS(status)) {
            case 120: case 121: case 122: why = "the judge could not start it as the test user"; break;
            case 123: why = "the kernel refused the judge's seccomp filter: this machine cannot confine it"; break;
            case 124: why = "its program could not be started"; break;
            default:
                why = "your code ended the program (exit code " + std::to_string(WEXITSTATUS(status)) +
                      "): a function must return its answer, never end the program";
            }
        } else if (WIFSIGNALED(status)) {
            const int sig = WTERMSIG(status);
            if (sig == SIGXCPU || sig == SIGKILL)
                why = "your code ran out of time (" + std::string(sig == SIGXCPU ? "SIGXCPU" : "SIGKILL") +
                      "): look for a loop that never ends";
            else if (sig == SIGSEGV || sig == SIGBUS)
                why = "your code crashed (" + std::string(sig == SIGSEGV ? "SIGSEGV" : "SIGBUS") +
                      "): an index out of range, or a null or dangling pointer";
            else if (sig == SIGABRT)
                why = "your code aborted (SIGABRT): a failed assert, or std::terminate after an exception "
                      "thrown from a noexcept function";
            else if (sig == SIGFPE)
                why = "your code crashed (SIGFPE): an integer division by zero";
            else
                why = "your code's program was ended by signal " + std::to_string(sig);
        }
        pid_ = -1;
        broken_ = why;
        return why;
    }

    void stop()
    {
        link_.reset();
        if (to_ >= 0)
            ::close(to_);
        if (from_ >= 0)
            ::close(from_);
        to_ = from_ = -1;
        if (pid_ > 0) {
            ::kill(pid_, SIGKILL);
            int status = 0;
            ::waitpid(pid_, &status, 0);
            pid_ = -1;
        }
    }

    std::unique_ptr<endpoint> link_;
    std::string broken_;
    pid_t pid_ = -1;
    int to_ = -1;
    int from_ = -1;
};

} // namespace judge
} // namespace rt

/// The judge's peer: the server starts at the first call of a case.
::rt::judge::peer& ::rt::judge::current_peer()
{
    static ::rt::judge::server_process process;
    static ::rt::judge::peer judge([]() -> ::rt::judge::endpoint& { return process.link(); });
    static const bool served = (rt_judge_table(judge), true);
    (void)served;
    return judge;
}
