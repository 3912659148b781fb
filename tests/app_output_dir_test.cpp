// OutputDir's guarantees about earlier outputs, on folders the tests write by hand (what a `run`
// writes, without rendering): a rerun moves aside exactly what the previous command wrote and
// leaves every other file where it is; each earlier run keeps a folder of its own, a killed one
// marked partial; per-scene CSVs move like every other output; the filesystem root and $HOME
// are refused. tests/integrity_check.sh checks the same on the fovrt executable.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "app/output_dir.h"
#include "core/error.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace fovrt;

namespace {

void Write(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

// One command into `dir` as `run` does it: lock, move the earlier outputs aside, write `files`
// (each holding `tag`), and the manifest when `complete`.
void FakeRun(const fs::path& dir, const std::string& tag, const std::vector<std::string>& files, bool complete = true) {
    OutputDir out(dir, "output.dir");
    out.Lock();
    out.MoveAsideEarlierOutputs(false);
    for (const std::string& file : files) Write(dir / file, tag);
    if (complete) Write(dir / "manifest.json", tag);
    out.Keep();
}

// FakeRun in a child process killed (SIGKILL) before it ends: no Keep, no destructor.
void KilledRun(const fs::path& dir, const std::string& tag, const std::vector<std::string>& files) {
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {  // the child never returns into Catch: killed, or exit 1 (not signalled) on an error
        try {
            OutputDir out(dir, "output.dir");
            out.Lock();
            out.MoveAsideEarlierOutputs(false);
            for (const std::string& file : files) Write(dir / file, tag);
            ::raise(SIGKILL);
        } catch (...) {
        }
        ::_exit(1);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    REQUIRE(WIFSIGNALED(status));
}

// The folders in `dir` named previous-run*, sorted.
std::vector<std::string> PreviousRuns(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().filename().string().rfind("previous-run", 0) == 0) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

const std::vector<std::string> kRunFiles = {"frames.jsonl", "inputs/f00000_left.exr", "inputs/f00000_right.exr",
                                            "denoised/svgf/f00000_left.png"};

std::string ErrorOf(const std::function<void()>& command) {
    try {
        command();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("a rerun never moves or deletes a file fovrt did not write, even inside its output folders") {
    const fs::path dir = test::ScratchDir("fovrt-output-dir") / "user-file";
    FakeRun(dir, "A", kRunFiles);
    Write(dir / "inputs" / "mydata.txt", "mine");
    FakeRun(dir, "B", kRunFiles);
    FakeRun(dir, "C", kRunFiles);
    CHECK(test::ReadFile(dir / "inputs" / "mydata.txt") == "mine");
    CHECK(test::ReadFile(dir / "inputs" / "f00000_left.exr") == "C");
    // Both earlier runs kept, whole, each in its own folder.
    const std::vector<std::string> previous = PreviousRuns(dir);
    REQUIRE(previous.size() == 2);
    CHECK(test::ReadFile(dir / previous[0] / "manifest.json") == "A");
    CHECK(test::ReadFile(dir / previous[1] / "manifest.json") == "B");
    for (const std::string& p : previous) {
        CHECK_FALSE(fs::exists(dir / p / "inputs" / "mydata.txt"));
        for (const std::string& file : kRunFiles) CHECK(fs::exists(dir / p / file));
    }
}

TEST_CASE("a run killed after a complete one: both kept apart, the killed one marked partial") {
    const fs::path dir = test::ScratchDir("fovrt-output-dir") / "killed";
    FakeRun(dir, "A", kRunFiles);
    KilledRun(dir, "B", {"frames.jsonl", "inputs/f00000_left.exr", "inputs/f00000_left.exr.tmp-7"});
    // Written beside a killed run, which could not list its own files: taken as the run's, so
    // moved with it (never deleted).
    Write(dir / "notes.txt", "mine");
    FakeRun(dir, "C", {"frames.jsonl", "inputs/f00000_left.exr"});
    const std::vector<std::string> previous = PreviousRuns(dir);
    REQUIRE(previous.size() == 2);
    std::string complete = previous[0], partial = previous[1];
    if (complete.find("-partial") != std::string::npos) std::swap(complete, partial);
    CHECK(complete.find("-partial") == std::string::npos);
    CHECK(partial.size() > std::string("-partial").size());
    CHECK(partial.substr(partial.size() - 8) == "-partial");
    CHECK(test::ReadFile(dir / complete / "manifest.json") == "A");
    CHECK(test::ReadFile(dir / complete / "inputs" / "f00000_right.exr") == "A");
    CHECK(test::ReadFile(dir / partial / "frames.jsonl") == "B");
    CHECK(fs::exists(dir / partial / "inputs" / "f00000_left.exr.tmp-7"));
    CHECK_FALSE(fs::exists(dir / partial / "manifest.json"));
    // The top holds C's outputs alone (and the user's file).
    CHECK(test::ReadFile(dir / "manifest.json") == "C");
    CHECK(test::ReadFile(dir / partial / "notes.txt") == "mine");
    CHECK_FALSE(fs::exists(dir / "inputs" / "f00000_left.exr.tmp-7"));
    CHECK_FALSE(fs::exists(dir / "inputs" / "f00000_right.exr"));
    CHECK_FALSE(fs::exists(dir / "denoised"));
}

TEST_CASE("an experiment's gaze-<scene>.csv moves aside with the rest of its outputs") {
    const fs::path dir = test::ScratchDir("fovrt-output-dir") / "gaze";
    FakeRun(dir, "room", {"frames-room.csv", "gaze-room.csv", "summary.json"});
    FakeRun(dir, "cornell", {"frames-cornell.csv", "gaze-cornell.csv", "summary.json"});
    CHECK_FALSE(fs::exists(dir / "gaze-room.csv"));
    CHECK_FALSE(fs::exists(dir / "frames-room.csv"));
    CHECK(test::ReadFile(dir / "gaze-cornell.csv") == "cornell");
    const std::vector<std::string> previous = PreviousRuns(dir);
    REQUIRE(previous.size() == 1);
    CHECK(test::ReadFile(dir / previous[0] / "gaze-room.csv") == "room");
}

TEST_CASE("a folder an older fovrt wrote (no ledger): its outputs move by name, into a folder of their own") {
    const fs::path dir = test::ScratchDir("fovrt-output-dir") / "no-ledger";
    for (const std::string& file : kRunFiles) Write(dir / file, "old");
    Write(dir / "manifest.json", "old");
    Write(dir / "gaze-room.csv", "old");
    Write(dir / "notes.txt", "mine");
    FakeRun(dir, "new", {"frames.jsonl"});
    const std::vector<std::string> previous = PreviousRuns(dir);
    REQUIRE(previous.size() == 1);
    CHECK(test::ReadFile(dir / previous[0] / "gaze-room.csv") == "old");
    CHECK(test::ReadFile(dir / previous[0] / "inputs" / "f00000_left.exr") == "old");
    CHECK(test::ReadFile(dir / "notes.txt") == "mine");
    CHECK(test::ReadFile(dir / "manifest.json") == "new");
}

TEST_CASE("a command that fails leaves the folder as it found it, and the next one moves nothing of it") {
    const fs::path dir = test::ScratchDir("fovrt-output-dir") / "failed";
    FakeRun(dir, "A", kRunFiles);
    Write(dir / "inputs" / "mydata.txt", "mine");
    {
        OutputDir out(dir, "output.dir");
        out.Lock();
        out.MoveAsideEarlierOutputs(false);
        Write(dir / "frames.jsonl", "B");
        Write(dir / "inputs" / "f00000_left.exr", "B");
    }  // no Keep: failed
    CHECK_FALSE(fs::exists(dir / "frames.jsonl"));
    CHECK_FALSE(fs::exists(dir / "inputs" / "f00000_left.exr"));
    CHECK(test::ReadFile(dir / "inputs" / "mydata.txt") == "mine");
    FakeRun(dir, "C", kRunFiles);
    CHECK(PreviousRuns(dir).size() == 1);  // A's; the failed command left nothing to keep
    CHECK(test::ReadFile(dir / "inputs" / "mydata.txt") == "mine");
}

TEST_CASE("the filesystem root and $HOME are refused as output folders, before anything is made") {
    CHECK_THAT(ErrorOf([] { OutputDir("/", "output.dir"); }),
               Catch::Matches("config key 'output.dir': '/' is the filesystem root; .*"));
    CHECK_THAT(ErrorOf([] { OutputDir("/tmp/..", "output.dir"); }), Catch::Contains("is the filesystem root"));
    const fs::path home = test::ScratchDir("fovrt-output-dir") / "home";
    fs::create_directories(home);
    const char* saved = std::getenv("HOME");
    const std::string savedHome = saved ? saved : "";
    ::setenv("HOME", home.c_str(), 1);
    CHECK_THAT(ErrorOf([&] { OutputDir(home / ".", "output.dir"); }),
               Catch::Contains("is the home folder ($HOME)"));
    CHECK(fs::is_empty(home));
    CHECK(ErrorOf([&] { OutputDir(home / "runs", "output.dir"); }).empty());  // a folder inside it is fine
    if (saved) ::setenv("HOME", savedHome.c_str(), 1);
    else ::unsetenv("HOME");
}
