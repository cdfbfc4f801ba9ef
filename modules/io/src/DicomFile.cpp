#include "DicomFile.h"

#include <string>

#include <vtkDICOMMetaData.h>
#include <vtkDICOMParser.h>
#include <vtkNew.h>

#include "FileChecks.h"
#include "VtkMessages.h"
#include "mvw/core/Error.h"

namespace mvw::io::detail {

ParsedDicomFile parseDicomFile(const std::filesystem::path& path, vtkDICOMMetaData* meta) {
  regularFileSize(path);
  VtkMessageScope messages;
  vtkNew<vtkDICOMParser> parser;
  parser->SetMetaData(meta);
  parser->SetFileName(path.c_str());
  // vtk-dicom allocates the length an element claims before it reads the value. Inside a value
  // of undefined length (scanned for its delimiter) it does not check that length against the
  // bytes left in the file, as it does elsewhere (vtkDICOMParser.cxx, SkipElements; v0.8.14 and
  // upstream alike): 3.4 GB for a 1.3 KB SEG (tests/fuzz/regressions). Where that allocation
  // fails, the file is refused like any other whose length fields claim too much.
  refuseOutOfMemory(path, [&] { parser->Update(); });
  if (!messages.firstError().empty() || parser->GetErrorCode() != 0) {
    const std::string why = messages.firstError();
    throw InputError(path,
                     "not a readable DICOM file" + (why.empty() ? std::string() : ": " + why));
  }
  return {parser->GetPixelDataFound() != 0, static_cast<long long>(parser->GetFileOffset()),
          parser->GetPixelDataVL()};
}

}  // namespace mvw::io::detail
