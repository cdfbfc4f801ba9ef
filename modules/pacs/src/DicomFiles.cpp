// The checks every received instance passes, with DCMTK's parser.
#include <cstdio>
#include <iostream>
#include <mutex>

#include <unistd.h>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcdicent.h>
#include <dcmtk/dcmdata/dcdict.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dctag.h>
#include <dcmtk/oflog/oflog.h>

#include "Internal.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"

namespace fs = std::filesystem;

namespace mvw::pacs::detail {

void quietDcmtk() {
  static std::once_flag once;
  std::call_once(once, [] { OFLog::configure(OFLogger::FATAL_LOG_LEVEL); });
}

std::optional<FileUids> readUids(const fs::path& file) {
  quietDcmtk();
  DcmFileFormat ff;
  // The whole file is parsed, so an instance whose Pixel Data (or anything) ends early is
  // refused here and never enters the verified cache: values longer than DCM_MaxReadLength
  // (the pixels) are not loaded, but their lengths are checked against the bytes the file
  // holds. Stopping at the Pixel Data tag, as this once did, let a truncated instance through.
  if (ff.loadFile(file.c_str(), EXS_Unknown, EGL_noChange, DCM_MaxReadLength, ERM_autoDetect).bad())
    return std::nullopt;
  DcmDataset* ds = ff.getDataset();
  OFString sop, series, study;
  if (ds->findAndGetOFString(DCM_SOPInstanceUID, sop).bad() || sop.empty()) return std::nullopt;
  ds->findAndGetOFString(DCM_SeriesInstanceUID, series);
  ds->findAndGetOFString(DCM_StudyInstanceUID, study);
  return FileUids{sop.c_str(), series.c_str(), study.c_str()};
}

std::string keywordOf(unsigned group, unsigned element) {
  const DcmDataDictionary& dict = dcmDataDict.rdlock();
  const DcmDictEntry* e =
      dict.findEntry(DcmTagKey(static_cast<Uint16>(group), static_cast<Uint16>(element)), nullptr);
  std::string name = e && e->getTagName() ? e->getTagName() : "";
  dcmDataDict.rdunlock();
  return name;
}

Receiver::Receiver(const Server& server, fs::path staging, Expect expect, bool progress)
    : server_(server),
      staging_(std::move(staging)),
      expect_(std::move(expect)),
      progress_(progress) {}

Receiver::~Receiver() {
  if (lineOpen_) std::fputc('\n', stderr);
}

void Receiver::acceptFile(const fs::path& file) {
  std::error_code ec;
  auto uids = readUids(file);
  auto refuse = [&](const std::string& why) {
    fs::remove(file, ec);
    throw ServiceError(server_.text + ": sent " + why);
  };
  if (!uids) refuse("an object that is not a DICOM file with a SOP Instance UID");
  // The UID names the file: only digits and dots, never a path component like "../x".
  if (!isUid(uids->sopInstance))
    refuse("an instance whose SOP Instance UID is not a UID ('" + uids->sopInstance.substr(0, 80) +
           "')");
  if (!expect_.studyUid.empty() && uids->study != expect_.studyUid)
    refuse("instance " + uids->sopInstance + " of study " + uids->study + ", not of study " +
           expect_.studyUid);
  if (!expect_.seriesUids.empty() && !expect_.seriesUids.count(uids->series))
    refuse("instance " + uids->sopInstance + " of series " + uids->series +
           ", not of a series asked for");
  const fs::path target = staging_ / (uids->sopInstance + ".dcm");
  bytes_ += fs::file_size(file, ec);
  fs::rename(file, target);
  if (received_.insert(uids->sopInstance).second) ++perSeries_[uids->series];
  report(false);
}

void Receiver::report(bool final) {
  if (onProgress_ && !final) onProgress_(transfer());
  if (!progress_) return;
  // A running line rewritten by carriage returns reads on a terminal only; in a log file it
  // is one long line of overprinted counts, so a file gets the final line alone.
  static const bool tty = ::isatty(STDERR_FILENO) != 0;
  if (!final && !tty) return;
  const auto now = std::chrono::steady_clock::now();
  if (!final && now - lastReport_ < std::chrono::milliseconds(500)) return;
  lastReport_ = now;
  const double s = std::chrono::duration<double>(now - start_).count();
  const double mb = static_cast<double>(bytes_) / 1e6;
  std::fprintf(stderr, "pacs: %s, %.1f MB, %.1f MB/s%s",
               mvw::countOf(static_cast<long long>(received_.size()), "instance").c_str(), mb,
               s > 0 ? mb / s : 0.0, final ? "\n" : "\r");
  lineOpen_ = !final;
  std::fflush(stderr);
}

Transfer Receiver::transfer() const {
  Transfer t;
  t.instances = static_cast<int>(received_.size());
  t.bytes = bytes_;
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return t;
}

}  // namespace mvw::pacs::detail
