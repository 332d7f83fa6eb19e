// verdict.cpp - how a judge tells the grader what each case did
// (tools/grading/judge/README.md).
//
// Linked into every judge: a doctest listener that writes one line a case to
// the file descriptor named by RT_JUDGE_VERDICT_FD, which the grader opened
// and nothing else holds (the server closes every descriptor before it runs a
// line of the student's code), and a last line when the run ends:
//
//     case <TAB> passed 0|1 <TAB> assertions <TAB> failed assertions <TAB> failure flags
//     end <TAB> cases passed <TAB> cases failed
//
// The grader passes a case only on this line, never on the judge's output.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include <unistd.h>

namespace {

int verdict_fd()
{
    const char* text = std::getenv("RT_JUDGE_VERDICT_FD");
    if (text == nullptr || *text == '\0')
        return -1;
    char* end = nullptr;
    const long fd = std::strtol(text, &end, 10);
    return *end == '\0' && fd > 2 ? int(fd) : -1;
}

void say(const std::string& line)
{
    const int fd = verdict_fd();
    if (fd < 0)
        return;
    const char* at = line.data();
    std::size_t left = line.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, at, left);
        if (n <= 0)
            return;
        at += n;
        left -= std::size_t(n);
    }
}

struct verdict_listener : doctest::IReporter {
    explicit verdict_listener(const doctest::ContextOptions&) {}

    void report_query(const doctest::QueryData&) override {}
    void test_run_start() override {}
    void test_run_end(const doctest::TestRunStats& stats) override
    {
        say("end\t" + std::to_string(stats.numTestCasesPassingFilters - stats.numTestCasesFailed) + "\t" +
            std::to_string(stats.numTestCasesFailed) + "\n");
    }
    void test_case_start(const doctest::TestCaseData&) override {}
    void test_case_reenter(const doctest::TestCaseData&) override {}
    void test_case_end(const doctest::CurrentTestCaseStats& stats) override
    {
        say("case\t" + std::to_string(stats.testCaseSuccess ? 1 : 0) + "\t" +
            std::to_string(stats.numAssertsCurrentTest) + "\t" + std::to_string(stats.numAssertsFailedCurrentTest) +
            "\t" + std::to_string(stats.failure_flags) + "\n");
    }
    void test_case_exception(const doctest::TestCaseException&) override {}
    void subcase_start(const doctest::SubcaseSignature&) override {}
    void subcase_end() override {}
    void log_assert(const doctest::AssertData&) override {}
    void log_message(const doctest::MessageData&) override {}
    void test_case_skipped(const doctest::TestCaseData&) override {}
};

} // namespace

REGISTER_LISTENER("rt_judge_verdict", 2, verdict_listener);
