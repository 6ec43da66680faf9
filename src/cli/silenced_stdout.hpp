// TetGen's loaders and mesher print to stdout, which the command and the
// bench use for their own output: while one of these objects lives, fd 1
// points at /dev/null.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

namespace bodt_cli {

class SilencedStdout {
public:
    SilencedStdout() {
        std::fflush(stdout);
        saved_ = dup(STDOUT_FILENO);
        const int null = open("/dev/null", O_WRONLY);
        if (null >= 0) {
            dup2(null, STDOUT_FILENO);
            close(null);
        }
    }
    ~SilencedStdout() {
        std::fflush(stdout);
        if (saved_ >= 0) {
            dup2(saved_, STDOUT_FILENO);
            close(saved_);
        }
    }
    SilencedStdout(const SilencedStdout&) = delete;
    SilencedStdout& operator=(const SilencedStdout&) = delete;

private:
    int saved_;
};

}  // namespace bodt_cli
