#pragma once
// Compressed DICOM pixel data decoded in a child process (issue 50): a decoder fault (GDCM's
// JPEG codec writing past its buffer, a loop, a memory blow-up) ends that process, not the one
// holding the user's work (the viewer, a Python session, a batch run). The child is the helper
// executable mvw-decoder (found as helperExecutable says), started per series with
// process::HelperProcess: limited in memory (RLIMIT_AS) and CPU time, killed at a wall-clock
// limit. It runs the same vtk-dicom reader on the same files and sends the voxels back over a
// socket; this process has sized the volume from the headers it read itself and takes exactly
// that many bytes, after a header that must match. A child that crashes, hits a limit or
// answers anything else is the file's error (InputError, exit 2). Native (uncompressed) pixel
// data is copied, not decoded, and is read in this process. (Internal to mvw_io.)
#include <filesystem>
#include <functional>

#include "mvw/core/Volume.h"

class vtkDICOMMetaData;
class vtkDICOMReader;

namespace mvw::io::detail {

// Whether any file the reader holds has a compressed transfer syntax (JPEG, JPEG-LS, JPEG 2000,
// RLE and any other that is not native or deflated): its pixels are decoded in the child.
bool hasCompressedPixelData(vtkDICOMMetaData* meta);

// The reader's output (after UpdateInformation, as configured: files, stack, rescale), decoded
// by mvw-decoder, as a volume with worldFromIndex identity. `input` is what the user named (the
// file or folder, for the messages); `first` the series' first file.
Volume decodeInChild(vtkDICOMReader* reader, const std::filesystem::path& input,
                     const std::filesystem::path& first);

// mvw-decoder's main: the child's end (process::helperSocket, then serveDecoder).
int decoderMain(int argc, char** argv);

// Answers one request on `fd` and ends the process: exit 0 after sending the voxels or the
// reader's error, 4 when an allocation failed (its memory limit). `beforeDecoding`, run after
// the request is read, is the tests' way in: a helper of their own (tests/io/
// decoder_faults_main.cpp) makes a real child crash, hang, blow its memory or lie there.
[[noreturn]] void serveDecoder(int fd, const std::function<void(int fd)>& beforeDecoding = {});

}  // namespace mvw::io::detail
