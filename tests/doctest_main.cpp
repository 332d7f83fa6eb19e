// The doctest runner shared by every suite (compiled once), with honest skips.
//
// A case skips with RT_SKIP(reason) (rt_skip.hpp): it prints "SKIPPED:
// reason" and returns at once. Each case ends passed, failed or skipped, and a
// failure wins: a case that skipped after a failed check is failed. The exit
// code is 1 when a case failed, 77 when every case that ran skipped (ctest's
// SKIP_RETURN_CODE, cmake/RtTestCases.cmake), else 0. ctest runs one case per test.
//
// --not-done-skips (the library suites, which call no exercise of their own):
// a case whose only failures are rt::exercise_not_done, a kit's unwritten
// exercise reached through the library, skips instead of failing. A stage's
// suite keeps them failures: they are its grade.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "rt_skip.hpp"

#include <cstring>
#include <iostream>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <rt/core/error.hpp>

namespace {

enum class verdict { passed, failed, skipped };

/// What the cases of this run did (the listener below writes it, RT_SKIP and the
/// exception translator too, from any thread a case starts).
struct run_record {
    std::mutex lock;
    bool not_done_skips = false;
    bool in_case = false;
    // the case running now
    std::string skip_reason;
    std::set<std::string> not_done_messages; // what rt::exercise_not_done said
    int not_done_asserts = 0;                // failed checks that threw one
    int not_done_exceptions = 0;             // the case ended by one
    int other_exceptions = 0;
    // the run
    int passed = 0, failed = 0, skipped = 0, skipped_not_done = 0;
    std::vector<std::string> skipped_names;
};

run_record& record()
{
    static run_record r;
    return r;
}

/// doctest quotes the message of an exception a check threw.
std::string unquoted(const doctest::String& text)
{
    std::string s = text.c_str();
    if (s.size() >= 2 && s.front() == '"' && s.back() == '"')
        s = s.substr(1, s.size() - 2);
    return s;
}

/// Judges each case as it ends (passed, failed or skipped) beside doctest's own reporter.
struct skip_listener : doctest::IReporter {
    explicit skip_listener(const doctest::ContextOptions&) {}

    void report_query(const doctest::QueryData&) override {}
    void test_run_start() override {}
    void test_run_end(const doctest::TestRunStats&) override {}
    void test_case_start(const doctest::TestCaseData& data) override
    {
        run_record& r = record();
        const std::lock_guard<std::mutex> guard(r.lock);
        r.in_case = true;
        r.skip_reason.clear();
        r.not_done_messages.clear();
        r.not_done_asserts = r.not_done_exceptions = r.other_exceptions = 0;
        name = data.m_name;
    }
    void test_case_reenter(const doctest::TestCaseData&) override {}
    void test_case_end(const doctest::CurrentTestCaseStats& stats) override
    {
        run_record& r = record();
        const std::lock_guard<std::mutex> guard(r.lock);
        r.in_case = false;
        const int explained = doctest::TestCaseFailureReason::AssertFailure | doctest::TestCaseFailureReason::Exception;
        const bool only_not_done = (stats.failure_flags & ~explained) == 0 && r.other_exceptions == 0 &&
                                   stats.numAssertsFailedCurrentTest <= r.not_done_asserts &&
                                   (r.not_done_asserts > 0 || r.not_done_exceptions > 0);
        verdict v = verdict::passed;
        if (!stats.testCaseSuccess)
            v = r.not_done_skips && only_not_done ? verdict::skipped : verdict::failed;
        else if (!r.skip_reason.empty())
            v = verdict::skipped;
        if (v == verdict::passed) {
            ++r.passed;
        } else if (v == verdict::failed) {
            ++r.failed;
            if (!r.skip_reason.empty())
                std::cout << "[rt] failed, not skipped: a check failed besides the skip (" << r.skip_reason << ")\n";
        } else {
            ++r.skipped;
            if (!stats.testCaseSuccess) {
                ++r.skipped_not_done;
                std::cout << "SKIPPED: this case waits for an exercise not written yet ("
                          << *r.not_done_messages.begin() << "); the library suites count it skipped\n";
            }
            r.skipped_names.push_back(name);
        }
        std::cout << std::flush;
    }
    void test_case_exception(const doctest::TestCaseException& e) override
    {
        run_record& r = record();
        const std::lock_guard<std::mutex> guard(r.lock);
        if (!e.is_crash && r.not_done_messages.count(e.error_string.c_str()))
            ++r.not_done_exceptions;
        else
            ++r.other_exceptions;
    }
    void subcase_start(const doctest::SubcaseSignature&) override {}
    void subcase_end() override {}
    void log_assert(const doctest::AssertData& a) override
    {
        if (!a.m_failed || !a.m_threw)
            return;
        run_record& r = record();
        const std::lock_guard<std::mutex> guard(r.lock);
        if (r.not_done_messages.count(unquoted(a.m_exception)))
            ++r.not_done_asserts;
    }
    void log_message(const doctest::MessageData&) override {}
    void test_case_skipped(const doctest::TestCaseData&) override {}

    std::string name;
};

} // namespace

REGISTER_LISTENER("rt_skips", 1, skip_listener);

// The message doctest prints is what() as before; the translator notes it, so
// the listener can tell an unwritten exercise from any other failure.
REGISTER_EXCEPTION_TRANSLATOR(const rt::exercise_not_done& e)
{
    run_record& r = record();
    const std::lock_guard<std::mutex> guard(r.lock);
    r.not_done_messages.insert(e.what());
    return doctest::String(e.what());
}

namespace rt_test {

void skip_case(const std::string& reason)
{
    run_record& r = record();
    const std::lock_guard<std::mutex> guard(r.lock);
    const std::string why = reason.empty() ? std::string("(no reason given)") : reason;
    std::cout << "SKIPPED: " << why << std::endl;
    if (r.in_case && r.skip_reason.empty())
        r.skip_reason = why;
}

} // namespace rt_test

int main(int argc, char** argv)
{
    std::vector<char*> args;
    for (int k = 0; k < argc; ++k) {
        if (k > 0 && std::strcmp(argv[k], "--not-done-skips") == 0)
            record().not_done_skips = true;
        else
            args.push_back(argv[k]);
    }
    doctest::Context context(int(args.size()), args.data());
    const int code = context.run();
    if (context.shouldExit())
        return code;
    run_record& r = record();
    const std::lock_guard<std::mutex> guard(r.lock);
    if (r.failed > 0)
        return code != 0 ? code : 1;
    if (code != 0 && r.skipped_not_done == 0) // doctest failed the run for a reason of its own
        return code;
    if (r.skipped == 0)
        return 0;
    std::cout << "[rt] " << r.skipped << " case" << (r.skipped == 1 ? "" : "s") << " skipped, " << r.passed
              << " passed, none failed (skipped: ";
    for (std::size_t k = 0; k < r.skipped_names.size(); ++k)
        std::cout << (k ? "; " : "") << r.skipped_names[k];
    std::cout << ")" << std::endl;
    return r.passed == 0 ? 77 : 0;
}
