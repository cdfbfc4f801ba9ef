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
  parser->Update();
  if (!messages.firstError().empty() || parser->GetErrorCode() != 0) {
    const std::string why = messages.firstError();
    throw InputError(path,
                     "not a readable DICOM file" + (why.empty() ? std::string() : ": " + why));
  }
  return {parser->GetPixelDataFound() != 0, static_cast<long long>(parser->GetFileOffset()),
          parser->GetPixelDataVL()};
}

}  // namespace mvw::io::detail
