#pragma once
// What the CLI tests share: a program's result, shell quoting for the command lines they run,
// running one with its output captured, a fresh folder per test, and reading a file whole.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

// A fresh, empty folder under GoogleTest's temporary folder: PREFIX_TEST_PID for the running
// test (PREFIX_PID outside one, as in a suite's set-up).
inline std::filesystem::path fresh_test_dir(const std::string& prefix) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = prefix + "_";
    if (info) name.append(info->name()).append("_");
    name.append(std::to_string(::getpid()));
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A test with a fresh, empty folder of its own (dir_: fresh_test_dir(prefix)), removed after it.
class TempDirTest : public ::testing::Test {
protected:
    explicit TempDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
    void SetUp() override { dir_ = fresh_test_dir(prefix_); }
    void TearDown() override {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    std::filesystem::path dir_;

private:
    std::string prefix_;
};

}  // namespace fresnel::test
