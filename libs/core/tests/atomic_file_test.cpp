// write_file_atomically: whole or absent, the original kept on failure, unique temporaries per
// thread, errors naming the destination.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/error.h"

using namespace fresnel;
namespace fs = std::filesystem;

namespace {
std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
struct Scratch {
    fs::path dir = fs::temp_directory_path() / ("fresnel_atomic_" + std::to_string(::getpid()));
    Scratch() { fs::create_directories(dir); }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    std::size_t entries() const {
        return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
    }
};
}  // namespace

TEST(AtomicFile, WritesAndReplacesWhole) {
    Scratch s;
    const fs::path f = s.dir / "out.txt";
    write_file_atomically(f, std::string_view("first"));
    EXPECT_EQ(read_text(f), "first");
    write_file_atomically(f, std::string_view("second, longer"));
    EXPECT_EQ(read_text(f), "second, longer");
    EXPECT_EQ(s.entries(), 1u);  // no temporary left behind
}

TEST(AtomicFile, AFailedWriteLeavesTheOriginalAndNoTemporary) {
    Scratch s;
    const fs::path f = s.dir / "image.png";
    write_file_atomically(f, std::string_view("the good one"));
    try {
        write_file_atomically(f, [](const fs::path& tmp) {
            EXPECT_EQ(tmp.extension(), ".png");  // writers that look at the extension see it
            EXPECT_EQ(tmp.parent_path(), fs::path(tmp).parent_path());
            std::ofstream(tmp) << "half";
            throw Error(tmp.string(), "row 7", "the disk is full");
        });
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), f.string());  // the destination, not the temporary
        EXPECT_EQ(e.where(), "row 7");
        EXPECT_EQ(e.reason(), "the disk is full");
    }
    EXPECT_EQ(read_text(f), "the good one");
    EXPECT_EQ(s.entries(), 1u);
}

TEST(AtomicFile, AnUnwritableFolderIsAnErrorNamingTheDestination) {
    Scratch s;
    const fs::path f = s.dir / "no" / "such" / "folder" / "x.bin";
    const std::vector<std::uint8_t> bytes = {1, 2, 3};
    try {
        write_file_atomically(f, std::span<const std::uint8_t>(bytes));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), f.string());
    }
    EXPECT_FALSE(fs::exists(f));
}

TEST(AtomicFile, TemporariesAreUniquePerThread) {
    const fs::path f = "/somewhere/out.exr";
    std::set<std::string> names;
    std::mutex m;
    std::vector<std::thread> threads;
    for (int i = 0; i < 8; ++i)
        threads.emplace_back([&] {
            const std::string n = temporary_path_beside(f).string();
            std::lock_guard lock(m);
            names.insert(n);
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(names.size(), 8u);
    for (const auto& n : names) {
        EXPECT_EQ(fs::path(n).parent_path(), "/somewhere");
        EXPECT_EQ(fs::path(n).extension(), ".exr");
        EXPECT_EQ(fs::path(n).filename().string().front(), '.');
    }
}

TEST(AtomicFile, ThreadsWritingOneFileLeaveOneWholeVersion) {
    Scratch s;
    const fs::path f = s.dir / "shared.txt";
    std::vector<std::thread> threads;
    std::atomic<int> failures{0};
    for (int i = 0; i < 8; ++i)
        threads.emplace_back([&, i] {
            const std::string text(4096 + i, char('a' + i));
            for (int k = 0; k < 20; ++k) {
                try {
                    write_file_atomically(f, std::string_view(text));
                } catch (const Error&) {
                    ++failures;
                }
            }
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(failures.load(), 0);
    const std::string text = read_text(f);
    ASSERT_FALSE(text.empty());
    const int i = text.front() - 'a';
    EXPECT_EQ(text, std::string(4096 + i, char('a' + i)));  // one writer's whole content
    EXPECT_EQ(s.entries(), 1u);
}
