#include "CheckedDicomReader.h"

#include <cstring>
#include <filesystem>
#include <vector>

#include <vtkDICOMConfig.h>
#include <vtkErrorCode.h>
#include <vtkObjectFactory.h>

#if defined(DICOM_USE_GDCM)
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#endif

namespace mvw::io::detail {

vtkStandardNewMacro(CheckedDicomReader);

bool CheckedDicomReader::ReadFileDelegated(const char* filename, int fileIdx, unsigned char* buffer,
                                           vtkIdType bufferSize) {
#if defined(DICOM_USE_GDCM)
  (void)fileIdx;
  // What vtk-dicom goes on to do with the buffer after a failure (mask bits, YBR to RGB) reads
  // zeros, not memory nothing wrote.
  auto refuse = [&]() {
    std::memset(buffer, 0, static_cast<std::size_t>(bufferSize));
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    return false;
  };
  gdcm::ImageReader reader;
  reader.SetFileName(filename);
  if (!reader.Read()) {
    vtkErrorMacro("GDCM could not read the image of " << filename);
    return refuse();
  }
  const gdcm::Image& image = reader.GetImage();
  const auto length = static_cast<vtkIdType>(image.GetBufferLength());
  if (length < bufferSize) {
    vtkErrorMacro("the decoded image of " << filename << " would be " << length
                                          << " bytes, the DICOM header says " << bufferSize);
    return refuse();
  }
  // GDCM writes its whole length: where that is more than the header asks for, into a buffer of
  // its own (vtk-dicom gave it the caller's, which is only bufferSize long).
  std::vector<char> larger;
  if (length > bufferSize) larger.resize(static_cast<std::size_t>(length));
  char* into = larger.empty() ? reinterpret_cast<char*>(buffer) : larger.data();
  if (!image.GetBuffer(into)) {
    // The file by its name alone: the message already names the series' first file.
    vtkErrorMacro("GDCM could not decode the compressed pixel data of "
                  << std::filesystem::path(filename).filename().string() << " (transfer syntax "
                  << image.GetTransferSyntax().GetString() << ")");
    return refuse();
  }
  if (!larger.empty()) std::memcpy(buffer, larger.data(), static_cast<std::size_t>(bufferSize));
  return true;
#else
  return vtkDICOMReader::ReadFileDelegated(filename, fileIdx, buffer, bufferSize);
#endif
}

}  // namespace mvw::io::detail
