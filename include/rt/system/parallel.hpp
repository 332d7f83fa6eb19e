// parallel.hpp - parallel_for: the one way rt starts threads. The renderer's
// tiles, the BVH builder's subtrees and the benchmarks' rays all go through it.
//
// Usage:
//     std::vector<scratch> per_worker(rt::thread_count(0));
//     rt::parallel_for(tiles.size(), int(per_worker.size()), [&](std::size_t tile, int worker) {
//         render_tile(tiles[tile], per_worker[worker]);       // worker in [0, threads)
//     });
//     rt::parallel_for(n, threads, body, [&] { report(); }); // the caller reports about 4 times a second
//
// Items are handed out one at a time through an atomic counter, so a slow item
// does not hold the others back and no thread idles while items are left. The
// calling thread works as one of the `threads`, unless a `tick` is given: then
// it starts `threads` workers and calls tick() every quarter second while it
// waits for them (a progress bar). The first exception a body throws (a bad
// scene, an unfinished exercise) stops the hand-out: the other threads finish
// the item they hold, and parallel_for rethrows it after every thread joined.
// A thread that cannot be started is reported the same way. Nothing is
// shared between the items but what the body shares: which thread runs an
// item is not deterministic, so a body whose result must not depend on the
// thread count writes only its own item's output.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace rt {

/// The thread count for `requested` (0 or less: all hardware threads, at least 1).
inline int thread_count(int requested)
{
    if (requested > 0)
        return requested;
    const unsigned hardware = std::thread::hardware_concurrency();
    return hardware > 0 ? int(hardware) : 1;
}

/// Calls body(item, worker) for every item in [0, count) on `threads` threads
/// (see the top of this file); worker numbers the thread, from 0 to threads - 1.
template <class Body>
void parallel_for(std::size_t count, int threads, Body&& body, const std::function<void()>& tick = {})
{
    if (count == 0)
        return;
    threads = int(std::min<std::size_t>(std::size_t(std::max(threads, 1)), count));
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr first_error, tick_error;
    std::mutex mutex; // guards first_error, running and the condition variable
    std::condition_variable finished;
    int running = 0;

    auto work = [&](int worker) {
        try {
            while (!failed.load()) {
                const std::size_t item = next.fetch_add(1);
                if (item >= count)
                    break;
                body(item, worker);
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex);
            if (!first_error)
                first_error = std::current_exception();
            failed.store(true);
        }
    };
    auto work_and_report = [&](int worker) {
        work(worker);
        {
            std::lock_guard<std::mutex> lock(mutex);
            --running;
        }
        finished.notify_one();
    };

    const bool caller_works = !tick;
    const int first_started = caller_works ? 1 : 0;
    std::vector<std::thread> pool;
    pool.reserve(std::size_t(threads));
    try {
        for (int worker = first_started; worker < threads; ++worker) {
            {
                std::lock_guard<std::mutex> lock(mutex);
                ++running;
            }
            try {
                pool.emplace_back(work_and_report, worker);
            } catch (...) {
                std::lock_guard<std::mutex> lock(mutex);
                --running;
                throw;
            }
        }
    } catch (...) { // could not start a thread: stop the others, then report
        failed.store(true);
        for (std::thread& thread : pool)
            thread.join();
        throw;
    }

    if (caller_works) {
        work(0);
    } else {
        std::unique_lock<std::mutex> lock(mutex);
        while (!finished.wait_for(lock, std::chrono::milliseconds(250), [&] { return running == 0; })) {
            lock.unlock();
            try {
                tick();
            } catch (...) { // the workers stop too; the tick's error is reported after theirs
                if (!tick_error)
                    tick_error = std::current_exception();
                failed.store(true);
            }
            lock.lock();
        }
    }
    for (std::thread& thread : pool)
        thread.join();
    if (first_error)
        std::rethrow_exception(first_error);
    if (tick_error)
        std::rethrow_exception(tick_error);
}

} // namespace rt
