#pragma once
// Each compressed frame's own header (JPEG and JPEG-LS SOF, JPEG 2000 SIZ, the RLE header)
// checked against the DICOM header before any decoder sees the frame. The decoders (GDCM
// through vtk-dicom) size their output buffer from Rows, Columns, SamplesPerPixel and
// BitsAllocated but decode what the stream's own header says: a JPEG whose SOF says 100 x 100
// in a 50 x 50 image writes past the buffer (issue 50). A frame that does not match is the
// file's error. The checks over bytes are pure; checkEncapsulatedFrames reads the file.
// (Internal to mvw_io.)
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace mvw::io::detail {

enum class FrameCodec { None, Jpeg, JpegLs, Jpeg2000, Rle };

// The codec a transfer syntax names; None for native, deflated and those not checked here
// (MPEG, HEVC: vtk-dicom does not decode them).
FrameCodec frameCodecOf(const std::string& transferSyntaxUid);

// What the DICOM header says every frame holds.
struct FrameLayout {
  long long rows = 0, columns = 0, samples = 1, bitsAllocated = 0;
};

struct FrameCheck {
  enum class Result { Matches, Mismatch, NeedMore };
  Result result = Result::Matches;
  std::string problem;  // Mismatch: what the frame's header says against the DICOM header
};

// `head` is the start of one frame (its fragments' bytes joined), `frameBytes` the frame's
// whole length. NeedMore: `head` ends before the header does and the frame goes on.
FrameCheck checkFrameHeader(FrameCodec codec, const FrameLayout& layout,
                            std::span<const std::uint8_t> head, std::uint64_t frameBytes);

// Whether a fragment beginning with `head` begins a frame of `codec` (a JPEG start-of-image, a
// JPEG 2000 codestream or JP2 signature): where fragments and frames are not one to one, the
// frames are found this way.
bool startsFrame(FrameCodec codec, std::span<const std::uint8_t> head);

// Every frame of the encapsulated pixel data of `file` (at most `frames` of them), checked;
// throws InputError naming the file, the frame and both sizes at the first mismatch. Reads the
// item headers and the first bytes of each frame, not the whole pixel data. A fragment list it
// cannot follow is left to the decoder's own checks.
void checkEncapsulatedFrames(const std::filesystem::path& file, FrameCodec codec,
                             const FrameLayout& layout, long long frames);

}  // namespace mvw::io::detail
