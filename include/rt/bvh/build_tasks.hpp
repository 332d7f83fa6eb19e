// bvh/build_tasks.hpp - the builder's threads: subtrees offered to idle
// threads, taken by whichever thread is free (work stealing).
//
// A large node of the binned build (binned_builder.hpp) offers its right
// child as a task, builds its left child, then joins the task: it builds the
// right child itself if no thread took it, and otherwise helps with other
// offered tasks until the thread that took it is done. An idle thread takes
// the oldest task offered, which is the largest subtree still waiting
// (Blumofe, Leiserson, "Scheduling Multithreaded Computations by Work
// Stealing", JACM 46(5), 1999). So no thread idles while a subtree of any
// size waits (docs/performance.md, experiment 6).
//
//     rt::detail::build_tasks tasks;
//     tasks.run(threads, [&] {                  // the root, on one of the threads
//         auto right_half = [&] { build(right); };
//         tasks.fork(right_half, [&] { build(left); }); // right_half offered meanwhile
//     });
//
// The threads are started by parallel_for (parallel.hpp); the tasks share one
// mutex, taken a few times per offered node (a node of thousands of
// primitives), never per primitive.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>

#include "../system/parallel.hpp"

namespace rt {
namespace detail {

/// A piece of work offered to other threads (build_tasks::fork). It refers
/// to `work`, which must outlive it.
class build_task {
public:
    template <class Work>
    explicit build_task(Work& work)
        : work_(&work), call_([](void* w) { (*static_cast<Work*>(w))(); })
    {
    }

private:
    friend class build_tasks;
    enum class state { offered, taken, done };

    void execute()
    {
        try {
            call_(work_);
        } catch (...) {
            error_ = std::current_exception(); // rethrown by join(), on the thread that offered it
        }
    }

    void* work_;
    void (*call_)(void*);
    state state_ = state::offered; // guarded by build_tasks::mutex_
    std::exception_ptr error_;
};

/// The threads of one build and the tasks they share (see the top of this file).
class build_tasks {
public:
    /// Calls root() on one thread while threads - 1 others take the tasks it
    /// offers (and those their tasks offer); returns when root() has returned,
    /// after the other threads have stopped. An exception from root() or from
    /// a task it joined is rethrown here.
    template <class Root>
    void run(int threads, Root&& root)
    {
        if (threads <= 1) {
            root();
            return;
        }
        // the first thread to start runs the root, the others help: so the
        // root runs even if parallel_for could not start every thread
        std::atomic<bool> root_taken{false};
        parallel_for(std::size_t(threads), threads, [&](std::size_t, int) {
            if (root_taken.exchange(true)) {
                help_until_finished();
                return;
            }
            struct finish_on_exit {
                build_tasks& tasks;
                ~finish_on_exit() { tasks.finish(); }
            } finish{*this};
            root();
        });
    }

    /// Calls left() here while `right` (a callable) is offered to the other
    /// threads; returns when both have returned. An exception from either is
    /// rethrown here, after both are done.
    template <class Right, class Left>
    void fork(Right& right, Left&& left)
    {
        build_task task(right);
        offer(task);
        try {
            left();
        } catch (...) {
            join(task, false); // it refers to this frame: taken back, or finished, before the frame goes
            throw;
        }
        join(task);
    }

private:
    /// Puts `task` where an idle thread can take it.
    void offer(build_task& task)
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            offered_.push_back(&task);
        }
        changed_.notify_one();
    }

    /// Returns when `task` is done: runs it here if no thread took it (or,
    /// with run = false, drops it), else helps with other offered tasks while
    /// the thread that took it works. Rethrows the task's exception if run.
    void join(build_task& task, bool run = true)
    {
        std::unique_lock<std::mutex> lock(mutex_);
        if (task.state_ == build_task::state::offered) {
            // still ours: the newest offers are at the back
            for (auto it = offered_.end(); it != offered_.begin();)
                if (*--it == &task) {
                    offered_.erase(it);
                    break;
                }
            lock.unlock();
            if (!run)
                return;
            task.execute();
        } else {
            while (task.state_ != build_task::state::done) {
                if (offered_.empty())
                    changed_.wait(lock);
                else
                    run_oldest(lock);
            }
        }
        if (task.error_ && run)
            std::rethrow_exception(task.error_);
    }

    /// Takes the oldest offered task and runs it with the mutex released.
    /// Precondition: `lock` holds mutex_ and a task is offered.
    void run_oldest(std::unique_lock<std::mutex>& lock)
    {
        build_task* task = offered_.front();
        offered_.pop_front();
        task->state_ = build_task::state::taken;
        lock.unlock();
        task->execute();
        lock.lock();
        task->state_ = build_task::state::done;
        changed_.notify_all(); // the thread that offered it may be waiting in join()
    }

    void help_until_finished()
    {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            if (!offered_.empty())
                run_oldest(lock);
            else if (finished_)
                return;
            else
                changed_.wait(lock);
        }
    }

    void finish()
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            finished_ = true;
        }
        changed_.notify_all();
    }

    std::mutex mutex_; // guards offered_, finished_ and every task's state
    std::condition_variable changed_;
    std::deque<build_task*> offered_;
    bool finished_ = false;
};

} // namespace detail
} // namespace rt
