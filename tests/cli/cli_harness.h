#pragma once
// What the CLI tests share: a program's result, shell quoting for the command lines they run,
// running one with its output captured, a fresh folder per test, and reading a file whole.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "temp_dir.h"

namespace fresnel::test {

struct Result {
    int exit_code = -1;
    std::string out, err;
};

// A result for a failure message: the exit status, then stdout and stderr.
inline std::string show(const Result& r) {
    return "exit " + std::to_string(r.exit_code) + "\nstdout:\n" + r.out + "\nstderr:\n" + r.err;
}

// `s` in single quotes for /bin/sh.
inline std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// `program` as it is (a quoted path, or a plain command with its own words) and each of `args`
// quoted. (Appended piece by piece: GCC 12's -Wrestrict misfires on `" " + std::string` chains.)
inline std::string command_line(const std::string& program, const std::vector<std::string>& args) {
    std::string cmd = program;
    for (const auto& a : args) cmd.append(" ").append(quote(a));
    return cmd;
}

// Runs the /bin/sh command line `cmd` with stdin from /dev/null, its stdout and stderr captured
// through stdout.txt and stderr.txt in `dir`; the exit status is 128 + the signal when one
// killed it.
inline Result run_captured(const std::string& cmd, const std::filesystem::path& dir) {
    const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    std::string line = cmd;
    line.append(" >").append(quote(out.string())).append(" 2>").append(quote(err.string())).append(" </dev/null");
    const int status = std::system(line.c_str());
    Result r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
}

// A test with a fresh, empty folder of its own (dir_, a TempDir: tests/support/temp_dir.h),
// removed after it.
class TempDirTest : public ::testing::Test {
protected:
    explicit TempDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
    void SetUp() override {
        scratch_ = std::make_unique<TempDir>(prefix_);
        dir_ = scratch_->path();
    }
    void TearDown() override { scratch_.reset(); }
    std::filesystem::path dir_;

private:
    std::string prefix_;
    std::unique_ptr<TempDir> scratch_;
};

}  // namespace fresnel::test
