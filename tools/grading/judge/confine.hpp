// confine.hpp - what the student's server may do: a seccomp filter that
// allows little more than reading the judge's calls, writing the replies and
// using memory (tools/grading/judge/README.md).
//
// The judge starts the server so (start_server in judge.hpp): fork; in the
// child, the link's pipes become fds 3 (calls in) and 4 (replies out), 0-2
// /dev/null, every other fd closed; resource limits; the test user's uid and
// gid (when the judge is root); PR_SET_PDEATHSIG; no new privileges; then
// filter(true) below, and execve. The server's main adds filter(false), which
// refuses execve too, before it reads a call. The server is linked statically,
// so nothing it needs to start opens a file, and the filter refuses every open.
//
// A refused system call fails with EPERM (std::cout writes nothing, a
// std::thread throws); the program goes on and its answer is judged as any
// other. Linux only; x86-64 and arm64.
#pragma once

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <linux/audit.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace rt {
namespace judge {

constexpr int call_fd = 3;    // the server reads the judge's frames here
constexpr int reply_fd = 4;   // and writes its own here

#if defined(__x86_64__)
constexpr std::uint32_t audit_arch = AUDIT_ARCH_X86_64;
#elif defined(__aarch64__)
constexpr std::uint32_t audit_arch = AUDIT_ARCH_AARCH64;
#else
#error "the judge's filter knows x86-64 and arm64 only"
#endif

/// The filter's program. With `starting`, execve is allowed (the judge's child
/// calls it once to start the server); the server installs the one without.
inline std::vector<sock_filter> filter_program(bool starting)
{
    std::vector<sock_filter> p;
    auto op = [&](std::uint16_t code, std::uint32_t k, std::uint8_t jt = 0, std::uint8_t jf = 0) {
        p.push_back(sock_filter{code, jt, jf, k});
    };
    const std::uint32_t deny = SECCOMP_RET_ERRNO | (EPERM & SECCOMP_RET_DATA);
    const std::uint32_t kill = SECCOMP_RET_KILL_PROCESS;
    // another architecture's system call numbers mean other calls: end the process
    op(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, arch));
    op(BPF_JMP | BPF_JEQ | BPF_K, audit_arch, 1, 0);
    op(BPF_RET | BPF_K, kill);
    op(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, nr));
#if defined(__x86_64__)
    op(BPF_JMP | BPF_JGE | BPF_K, 0x40000000u, 0, 1);   // the x32 calls
    op(BPF_RET | BPF_K, kill);
#endif
    // read only the calls, write only the replies: the fd is args[0] (its high half 0)
    auto fd_only = [&](long nr, int fd) {
        op(BPF_JMP | BPF_JEQ | BPF_K, std::uint32_t(nr), 0, 6);
        op(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, args[0]) + 4);
        op(BPF_JMP | BPF_JEQ | BPF_K, 0, 0, 2);
        op(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, args[0]));
        op(BPF_JMP | BPF_JEQ | BPF_K, std::uint32_t(fd), 1, 0);
        op(BPF_RET | BPF_K, deny);
        op(BPF_RET | BPF_K, SECCOMP_RET_ALLOW);
        op(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, nr));   // for the next test
    };
    fd_only(__NR_read, call_fd);
    fd_only(__NR_write, reply_fd);
    // prctl only to add a filter (the server's own, which refuses more): a filter
    // can only take permissions away
    op(BPF_JMP | BPF_JEQ | BPF_K, std::uint32_t(__NR_prctl), 0, 5);
    op(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, args[0]));
    op(BPF_JMP | BPF_JEQ | BPF_K, std::uint32_t(PR_SET_SECCOMP), 2, 0);
    op(BPF_JMP | BPF_JEQ | BPF_K, std::uint32_t(PR_SET_NO_NEW_PRIVS), 1, 0);
    op(BPF_RET | BPF_K, deny);
    op(BPF_RET | BPF_K, SECCOMP_RET_ALLOW);
    op(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, nr));
    // memory, threads' bookkeeping, time, the end: what a static C++ program uses
    const long allowed[] = {
        __NR_brk, __NR_mmap, __NR_munmap, __NR_mremap, __NR_mprotect, __NR_madvise,
        __NR_futex, __NR_set_robust_list, __NR_set_tid_address,
#ifdef __NR_rseq
        __NR_rseq,
#endif
#ifdef __NR_arch_prctl
        __NR_arch_prctl,
#endif
        __NR_rt_sigprocmask, __NR_rt_sigreturn, __NR_sched_yield, __NR_clock_gettime, __NR_gettimeofday,
        __NR_getrandom, __NR_exit, __NR_exit_group,
    };
    for (long nr : allowed) {
        op(BPF_JMP | BPF_JEQ | BPF_K, std::uint32_t(nr), 0, 1);
        op(BPF_RET | BPF_K, SECCOMP_RET_ALLOW);
    }
    if (starting) {
        op(BPF_JMP | BPF_JEQ | BPF_K, std::uint32_t(__NR_execve), 0, 1);
        op(BPF_RET | BPF_K, SECCOMP_RET_ALLOW);
    }
    op(BPF_RET | BPF_K, deny);   // open, socket, kill, ptrace, clone, ...: refused
    return p;
}

/// Installs the filter on the calling thread (and what it starts); false when the
/// kernel refused it (errno says why).
inline bool install_filter(const std::vector<sock_filter>& program)
{
    if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0)
        return false;
    sock_fprog fprog{static_cast<unsigned short>(program.size()), const_cast<sock_filter*>(program.data())};
    return ::prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &fprog, 0, 0) == 0;
}

} // namespace judge
} // namespace rt
