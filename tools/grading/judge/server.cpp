// server.cpp - the program that runs a student's functions of one stage for
// the judge (remote.hpp; tools/grading/judge/README.md).
//
// Started by the judge only, already confined (confine.hpp): it reads calls on
// fd 3 and writes replies on fd 4 until the judge closes the link. Its first
// act refuses execve as well, so that nothing after it becomes another
// program. judge_table.hpp (written by tools/grading/judge.py) names the
// stage's functions; it is built with front.hpp included first.
#include "confine.hpp"
#include "remote.hpp"

#include "judge_table.hpp"

rt::judge::peer& rt::judge::current_peer()
{
    static rt::judge::endpoint link(rt::judge::call_fd, rt::judge::reply_fd);
    static rt::judge::peer server([]() -> rt::judge::endpoint& { return link; });
    return server;
}

namespace {
int& served_stage()
{
    static int stage = 0;
    return stage;
}
} // namespace

int rt::judge::serving_stage()
{
    return served_stage();
}

int main(int argc, char** argv)
{
    if (!rt::judge::install_filter(rt::judge::filter_program(false)))
        return 123;
    if (argc > 1) {
        int stage = 0;
        for (const char* c = argv[1]; *c >= '0' && *c <= '9' && stage < 100; ++c)
            stage = stage * 10 + (*c - '0');
        served_stage() = stage;
    }
    rt::judge::peer& server = rt::judge::current_peer();
    rt_judge_table(server);
    try {
        server.link().serve();
    } catch (const rt::judge::link_error&) {
        return 1;
    }
    return 0;
}
