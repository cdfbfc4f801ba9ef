// Bad files end in one InputError that names the file, before anything large is allocated.
#include <fstream>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/io/LabelTable.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"

namespace mvw::io {
namespace {

namespace fs = std::filesystem;

TEST(MaxBytes, OneMebibyteToOnePebibyte) {
  EXPECT_EQ(maxBytesProblem("1048576"), "");
  EXPECT_EQ(maxBytesProblem("1125899906842624"), "");
  const std::string why = "must be a size from 1M to 1P (e.g. 512M, 4G)";
  EXPECT_EQ(maxBytesProblem("1048575"), why);
  EXPECT_EQ(maxBytesProblem("1125899906842625"), why);
  EXPECT_EQ(maxBytesProblem("99999999999999999999999"), why);  // beyond 2^64
  EXPECT_EQ(maxBytesProblem("4G"), why);                       // not yet a byte count
  EXPECT_EQ(maxBytesProblem(""), why);
}

std::string refusal(const fs::path& p, const ReadOptions& options = {}) {
  try {
    readVolume(p, options);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(p.filename().string()), std::string::npos) << e.what();
    return e.problem();
  }
  ADD_FAILURE() << p << " was not refused";
  return {};
}

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

fs::path smallNifti(const fs::path& dir) {
  Volume v({9, 8, 7}, 1, ScalarType::Int16, glm::dmat4(1.0));
  writeVolume(v, dir / "good.nii");
  return dir / "good.nii";
}

TEST(BadInput, TruncatedNiftiIsRefusedWithSizes) {
  const fs::path dir = test::scratchDir();
  const std::string good = bytesOf(smallNifti(dir));
  std::ofstream(dir / "cut.nii", std::ios::binary) << good.substr(0, good.size() - 1);
  EXPECT_NE(refusal(dir / "cut.nii").find("truncated"), std::string::npos);
}

TEST(BadInput, HeaderLargerThanTheLimitIsRefusedBeforeReading) {
  const fs::path dir = test::scratchDir();
  const fs::path p = smallNifti(dir);
  ReadOptions tiny;
  tiny.maxBytes = 1000;  // the volume needs 9*8*7*2 = 1008 bytes
  EXPECT_NE(refusal(p, tiny).find("limit"), std::string::npos);
  tiny.maxBytes = 1008;
  EXPECT_NO_THROW(readVolume(p, tiny));
}

TEST(BadInput, MissingAndUnknownFiles) {
  const fs::path dir = test::scratchDir();
  EXPECT_NE(refusal(dir / "absent.nii").find("no such file"), std::string::npos);
  std::ofstream(dir / "notes.txt") << "hello";
  EXPECT_NE(refusal(dir / "notes.txt").find("unknown file type"), std::string::npos);
  fs::create_directories(dir / "empty-folder");
  EXPECT_NE(refusal(dir / "empty-folder").find("no DICOM image series"), std::string::npos);
}

TEST(BadInput, MetaImageWithTooLittleData) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "short.mha", std::ios::binary)
      << "ObjectType = Image\nNDims = 3\nDimSize = 10 10 10\nElementType = MET_FLOAT\n"
         "ElementDataFile = LOCAL\n"
      << std::string(100, '\0');
  EXPECT_NE(refusal(dir / "short.mha").find("truncated"), std::string::npos);
}

// Text voxels, a key given twice and a matrix of "nan" are refused, each by what it is.
TEST(BadInput, MetaImageHeadersThatLie) {
  const fs::path dir = test::scratchDir();
  const std::string head =
      "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\n";
  std::ofstream(dir / "text.mha", std::ios::binary)
      << head << "BinaryData = False\nElementDataFile = LOCAL\n1 2 3 4 5 6 7 8\n";
  EXPECT_NE(refusal(dir / "text.mha").find("BinaryData = False: the voxels are text"),
            std::string::npos);
  std::ofstream(dir / "twice.mha", std::ios::binary)
      << head << "Offset = 0 0 0\nOffset = 5 5 5\nElementDataFile = LOCAL\n"
      << std::string(8, '\0');
  EXPECT_EQ(refusal(dir / "twice.mha"), "the header gives Offset twice");
  std::ofstream(dir / "nan.mha", std::ios::binary)
      << head << "TransformMatrix = nan 0 0 0 1 0 0 0 1\nElementDataFile = LOCAL\n"
      << std::string(8, '\0');
  EXPECT_EQ(refusal(dir / "nan.mha"), "TransformMatrix holds nan, a value that is not finite");
  std::ofstream(dir / "word.mha", std::ios::binary)
      << head << "ElementSpacing = 1 one 1\nElementDataFile = LOCAL\n"
      << std::string(8, '\0');
  EXPECT_EQ(refusal(dir / "word.mha"), "ElementSpacing holds 'one', which is not a number");
}

// Label tables: any line ending (LF, CR LF, CR CR LF, CR alone); a bad line quoted with control
// characters shown; a name with a control character refused. A name given to two labels is
// read (atlases have them); only a glyph view choosing that name refuses it (ViewPlan).
TEST(BadInput, LabelTables) {
  const fs::path dir = test::scratchDir();
  auto table = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  };
  auto problem = [](const fs::path& p) -> std::string {
    try {
      readLabelTable(p);
    } catch (const InputError& e) {
      return e.problem();
    }
    return "accepted";
  };
  const auto crlf =
      readLabelTable(table("crlf.txt", "1 Precentral_L 2001\r\r\n2 Precentral_R\r\n\r\r\n"));
  ASSERT_EQ(crlf.size(), 2u);
  EXPECT_EQ(crlf.at(1), "Precentral_L");
  EXPECT_EQ(crlf.at(2), "Precentral_R");
  EXPECT_NE(problem(table("bad.txt", "1 A\nx\x01y\n")).find("line 2 is not \"NUMBER NAME\": 'x?y'"),
            std::string::npos);
  const auto cr = readLabelTable(table("cr.txt", "# header\r1 A\r2 B\r3 C\r"));
  EXPECT_EQ(cr.size(), 3u);
  EXPECT_EQ(cr.at(3), "C");
  EXPECT_NE(problem(table("line3.txt", "1 A\r\n2 B\r\nbad\r\n")).find("line 3 is not"),
            std::string::npos);
  EXPECT_EQ(readLabelTable(table("twice.txt", "1 A\n200 A\n")).size(), 2u);
  EXPECT_NE(problem(table("nul.txt", std::string("1 A\0B\n", 6))).find("control character"),
            std::string::npos);
}

}  // namespace
}  // namespace mvw::io
