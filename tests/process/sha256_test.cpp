// SHA-256 (process Sha256): the FIPS 180-2 vectors, a file as its bytes, a folder as its files'
// names and bytes in name order, and a file that cannot be read named with its role.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/process/Sha256.h"

namespace mvw::process {
namespace {

namespace fs = std::filesystem;

std::string sha(const std::string& bytes) {
  Sha256 s;
  s.add(bytes.data(), bytes.size());
  return s.hex();
}

TEST(Sha256, KnownVectors) {
  EXPECT_EQ(sha(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // Added in pieces, the same digest.
  Sha256 pieces;
  pieces.add("a", 1);
  pieces.add("bc", 2);
  EXPECT_EQ(pieces.hex(), sha("abc"));
}

TEST(Sha256, FilesAndFolders) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "abc.txt", std::ios::binary) << "abc";
  EXPECT_EQ(fileSha256(dir / "abc.txt"), sha("abc"));
  EXPECT_EQ(pathSha256(dir / "abc.txt"), sha("abc"));
  fs::create_directories(dir / "series" / "sub");
  std::ofstream(dir / "series" / "b.dcm", std::ios::binary) << "two";
  std::ofstream(dir / "series" / "a.dcm", std::ios::binary) << "one";
  std::ofstream(dir / "series" / "sub" / "c.dcm", std::ios::binary) << "three";
  EXPECT_EQ(pathSha256(dir / "series"),
            sha(std::string("a.dcm\0one", 9) + std::string("b.dcm\0two", 9) +
                std::string("sub/c.dcm\0three", 15)));
  try {
    fileSha256(dir / "none.txt", "an input of a batch study");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "none.txt").string() + ": cannot be read (an input of a batch study)");
  }
  EXPECT_THROW(fileSha256(dir / "none.txt"), InputError);
}

}  // namespace
}  // namespace mvw::process
