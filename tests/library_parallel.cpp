// rt::parallel_for (parallel.hpp): every item once, workers numbered within
// the thread count, the first exception rethrown after every thread stopped,
// and the caller's tick while it waits. Run under TSan in CI (label library).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <rt/system/parallel.hpp>

#include "rt_doctest.hpp"

TEST_CASE("parallel_for calls the body once for every item, with a worker number below the thread count")
{
    for (const int threads : {1, 2, 3, 8}) {
        for (const std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(5), std::size_t(1000)}) {
            CAPTURE(threads);
            CAPTURE(count);
            std::vector<std::atomic<int>> calls(count);
            std::atomic<int> bad_worker{0};
            rt::parallel_for(count, threads, [&](std::size_t item, int worker) {
                calls[item].fetch_add(1);
                if (worker < 0 || worker >= threads)
                    bad_worker.fetch_add(1);
            });
            int wrong = 0;
            for (const std::atomic<int>& c : calls)
                wrong += c.load() != 1;
            CHECK_MESSAGE(wrong == 0, "expected every item called exactly once; " << wrong << " were not");
            CHECK_MESSAGE(bad_worker.load() == 0, "expected worker numbers in [0, " << threads << ")");
        }
    }
}

TEST_CASE("parallel_for rethrows the first exception a body throws, after the other threads stopped")
{
    // Items after 10 wait until item 10 is about to throw, then take 1 ms each:
    // with the hand-out stopping at the failure, a few more start; without
    // it, all 10000 would. (Without the wait and the 1 ms, the test depended
    // on the scheduler: on a loaded machine the other threads raced through
    // every item before item 10's thread ran.)
    std::atomic<int> started{0};
    std::atomic<bool> throwing{false};
    bool thrown = false;
    std::string what;
    try {
        rt::parallel_for(10000, 4, [&](std::size_t item, int) {
            started.fetch_add(1);
            if (item == 10) {
                throwing.store(true);
                throw std::runtime_error("item 10 failed");
            }
            if (item > 10) {
                const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
                while (!throwing.load() && std::chrono::steady_clock::now() < give_up)
                    std::this_thread::yield();
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            }
        });
    } catch (const std::runtime_error& e) {
        thrown = true;
        what = e.what();
    }
    CHECK_MESSAGE(thrown, "expected the body's exception to reach the caller");
    CHECK(what == "item 10 failed");
    // the hand-out stops: far fewer than all 10000 items were started
    CHECK_MESSAGE(started.load() < 10000, "expected the other threads to stop after the failure, found all "
                                              << started.load() << " items started");
}

TEST_CASE("parallel_for with a tick: the caller ticks while the workers run, and a tick's exception is rethrown")
{
    std::atomic<int> ticks{0};
    rt::parallel_for(
        4, 2, [&](std::size_t, int) { std::this_thread::sleep_for(std::chrono::milliseconds(300)); },
        [&] { ticks.fetch_add(1); });
    CHECK_MESSAGE(ticks.load() >= 1, "expected at least one tick in 600 ms of work (one every 250 ms)");

    bool thrown = false;
    try {
        rt::parallel_for(
            4, 2, [&](std::size_t, int) { std::this_thread::sleep_for(std::chrono::milliseconds(300)); },
            [] { throw std::runtime_error("progress failed"); });
    } catch (const std::runtime_error& e) {
        thrown = std::string(e.what()) == "progress failed";
    }
    CHECK_MESSAGE(thrown, "expected the tick's exception to reach the caller once the workers stopped");
}

TEST_CASE("thread_count: a positive request is kept, 0 means every hardware thread (at least 1)")
{
    CHECK(rt::thread_count(3) == 3);
    CHECK(rt::thread_count(0) >= 1);
    CHECK(rt::thread_count(-2) == rt::thread_count(0));
}
