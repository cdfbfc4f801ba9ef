// io::installInterruptCleanup and io::RemovedOnInterrupt (issue 51 item 4), each case in a
// forked child so the signal ends that child alone: SIGINT and SIGTERM remove every registered
// path (a folder with what it holds, a file, a StagedFolder's and an AtomicFile's temporaries),
// keep those registered to be kept, say each on stderr and exit 130 / 143; a released path is
// left alone; a signal the process ignored stays ignored; a fork without exec dies of the
// signal as it would have without the handler.
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/io/Interrupt.h"
#include "mvw/io/StagedFolder.h"

namespace mvw::io {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs `body` in a child with its stderr in `err`; its wait status.
int inChild(const fs::path& err, const std::function<void()>& body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen(err.c_str(), "w", stderr);
    body();
    ::_exit(99);  // the signal did not end it
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

TEST(Interrupt, SigintRemovesEveryRegisteredPathKeepsTheKeptAndExits130) {
  const fs::path dir = test::scratchDir();
  fs::create_directories(dir / "staged" / "a" / "b");
  std::ofstream(dir / "staged" / "a" / "b" / "1.dcm") << "one";
  std::ofstream(dir / "staged" / "2.dcm") << "two";
  std::ofstream(dir / "tmp-file") << "x";
  fs::create_directories(dir / "cache.partial");
  std::ofstream(dir / "cache.partial" / "3.dcm") << "three";
  fs::create_directories(dir / "released");
  const int status = inChild(dir / "err.txt", [&] {
    installInterruptCleanup();
    RemovedOnInterrupt staged(dir / "staged"), file(dir / "tmp-file");
    RemovedOnInterrupt kept(dir / "cache.partial", RemovedOnInterrupt::Action::Keep);
    RemovedOnInterrupt released(dir / "released");
    released.release();
    ::raise(SIGINT);
  });
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_FALSE(fs::exists(dir / "staged"));
  EXPECT_FALSE(fs::exists(dir / "tmp-file"));
  EXPECT_TRUE(fs::exists(dir / "cache.partial" / "3.dcm"));
  EXPECT_TRUE(fs::exists(dir / "released"));
  const std::string err = read(dir / "err.txt");
  EXPECT_NE(err.find("mvw: interrupted (SIGINT): removed the unfinished " +
                     (dir / "staged").string() + "\n"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("mvw: interrupted (SIGINT): kept " + (dir / "cache.partial").string() +
                     " for the next run to resume\n"),
            std::string::npos)
      << err;
  EXPECT_EQ(err.find("released"), std::string::npos) << err;
}

TEST(Interrupt, SigtermInTheMiddleOfStagedOutputsLeavesNoneAndExits143) {
  const fs::path dir = test::scratchDir();
  const int status = inChild(dir / "err.txt", [&] {
    installInterruptCleanup();
    StagedFolder staging(dir / "out", {.purpose = "render"});
    std::ofstream(staging.path() / "view.png") << "png";
    writeAtomically(dir / "single.json", [&](const fs::path& tmp) {
      std::ofstream(tmp) << "{";
      ::raise(SIGTERM);
    });
  });
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 143);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename(), "err.txt") << "left behind: " << e.path();
  EXPECT_NE(read(dir / "err.txt").find("mvw: interrupted (SIGTERM): removed the unfinished "),
            std::string::npos);
}

TEST(Interrupt, NothingRegisteredIsSaidToo) {
  const fs::path dir = test::scratchDir();
  const int status = inChild(dir / "err.txt", [] {
    installInterruptCleanup();
    ::raise(SIGINT);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_EQ(read(dir / "err.txt"),
            "mvw: interrupted (SIGINT): nothing unfinished was left behind\n");
}

TEST(Interrupt, AnIgnoredSignalStaysIgnoredAndAForkDiesOfIt) {
  const fs::path dir = test::scratchDir();
  int status = inChild(dir / "err.txt", [] {
    std::signal(SIGINT, SIG_IGN);  // as nohup or a background job of a shell leave it
    installInterruptCleanup();
    ::raise(SIGINT);
    ::_exit(7);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7);
  status = inChild(dir / "err.txt", [&] {
    installInterruptCleanup();
    const RemovedOnInterrupt parents(dir);  // the forked copy must not remove its parent's
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::raise(SIGTERM);
      ::_exit(98);
    }
    int s = 0;
    ::waitpid(pid, &s, 0);
    ::_exit(WIFSIGNALED(s) && WTERMSIG(s) == SIGTERM ? 0 : 1);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_TRUE(fs::exists(dir));
}

}  // namespace
}  // namespace mvw::io
