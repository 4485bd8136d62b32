#include "bench/study_cli.h"

#include <cstdio>

#include "core/error.h"

namespace tyndall::bench {

int runStudy(CLI::App& cli, int argc, char** argv, const std::function<void()>& study) {
    try {
        cli.parse(argc, argv);
        study();
    } catch (const CLI::ParseError& e) {
        return cli.exit(e);
    } catch (const Error& e) {
        std::fprintf(stderr, "%s: %s\n", cli.get_name().c_str(), e.what());
        return 1;
    }
    return 0;
}

}  // namespace tyndall::bench
