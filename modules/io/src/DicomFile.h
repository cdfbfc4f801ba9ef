#pragma once
// One DICOM file's header through vtk-dicom's parser, with the one refusal every single-file
// reader gives (internal to mvw_io: vtk-dicom types stay inside this folder).
#include <filesystem>

#include "mvw/io/DicomSeg.h"

class vtkDICOMMetaData;

namespace mvw::io::detail {

struct ParsedDicomFile {
  bool pixelData = false;     // the parser met the PixelData element
  long long pixelOffset = 0;  // where its value starts in the file
  unsigned int pixelLength = 0;
};

// Parses `path` into `meta`. Throws InputError naming the file when it is not a regular file
// or vtk-dicom cannot parse it ("not a readable DICOM file: ..."), or a length field made the
// parser allocate more than the machine holds ("not enough memory ...").
ParsedDicomFile parseDicomFile(const std::filesystem::path& path, vtkDICOMMetaData* meta);

// readDicomSegmentation on a header parseDicomFile has already read (a reader that met the
// SEG's SOP class on its way need not parse the file a second time).
Segmentation segmentationFromHeader(const std::filesystem::path& path, vtkDICOMMetaData* meta,
                                    const ParsedDicomFile& parsed, const ReadOptions& options);

}  // namespace mvw::io::detail
