#pragma once
// vtk-dicom's reader with one fault of its own closed (issue 50): where vtk-dicom hands
// compressed pixel data to GDCM (vtkDICOMReader::ReadFileDelegated, vtk-dicom 0.8.14 to 0.8.17)
// it ignores whether GDCM decoded it. gdcm::Bitmap::GetBuffer returns false when every codec
// failed (a JPEG frame longer than the header allows: "Impossible length"), having left the
// buffer unwritten, and vtk-dicom went on to convert those bytes (YBR to RGB) into an image of
// uninitialised memory that "loaded" with no error (valgrind, tests/fuzz/valgrind-decoders).
// Here GDCM's answer is checked: a frame it cannot decode is the reader's error (the file's
// InputError, exit 2), and the buffer holds zeros, never unwritten memory, for what vtk-dicom
// still does with it before the error is seen. Only the GDCM path (DICOM_USE_GDCM, Debian's
// vtk-dicom) is replaced; vtk-dicom's DCMTK path checks its decoder already. Used wherever mvw
// decodes DICOM pixels: the decoder child (IsolatedDecoder.h) and the in-process read
// (DicomSeries.cpp). (Internal to mvw_io.)
#include <vtkDICOMReader.h>

namespace mvw::io::detail {

class CheckedDicomReader : public vtkDICOMReader {
 public:
  static CheckedDicomReader* New();
  vtkTypeMacro(CheckedDicomReader, vtkDICOMReader)

 protected:
  CheckedDicomReader() = default;
  ~CheckedDicomReader() override = default;

  bool ReadFileDelegated(const char* filename, int fileIdx, unsigned char* buffer,
                         vtkIdType bufferSize) override;

 public:
  CheckedDicomReader(const CheckedDicomReader&) = delete;
  CheckedDicomReader& operator=(const CheckedDicomReader&) = delete;
};

}  // namespace mvw::io::detail
