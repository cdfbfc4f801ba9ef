// The checks every received instance passes, with DCMTK's parser.
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <limits>
#include <mutex>
#include <set>
#include <string>

#include <unistd.h>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcdicent.h>
#include <dcmtk/dcmdata/dcdict.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcpixel.h>
#include <dcmtk/dcmdata/dcpixseq.h>
#include <dcmtk/dcmdata/dcpxitem.h>
#include <dcmtk/dcmdata/dctag.h>
#include <dcmtk/dcmdata/dcxfer.h>
#include <dcmtk/oflog/oflog.h>

#include "Internal.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/io/PixelData.h"

namespace fs = std::filesystem;

namespace mvw::pacs::detail {

void quietDcmtk() {
  static std::once_flag once;
  std::call_once(once, [] { OFLog::configure(OFLogger::FATAL_LOG_LEVEL); });
}

namespace {

// The whole file is parsed, so an instance whose Pixel Data (or anything) ends early is
// refused and never enters the verified cache: values longer than DCM_MaxReadLength (the
// pixels) are not loaded, but their lengths are checked against the bytes the file holds, and
// an encapsulated Pixel Data without its sequence delimiter does not parse. Stopping at the
// Pixel Data tag, as this once did, let a truncated instance through.
OFCondition loadWhole(DcmFileFormat& ff, const fs::path& file) {
  quietDcmtk();
  return ff.loadFile(file.c_str(), EXS_Unknown, EGL_noChange, DCM_MaxReadLength, ERM_autoDetect);
}

std::optional<FileUids> uidsOf(DcmDataset& ds) {
  OFString sop, series, study;
  if (ds.findAndGetOFString(DCM_SOPInstanceUID, sop).bad() || sop.empty()) return std::nullopt;
  ds.findAndGetOFString(DCM_SeriesInstanceUID, series);
  ds.findAndGetOFString(DCM_StudyInstanceUID, study);
  return FileUids{sop.c_str(), series.c_str(), study.c_str()};
}

std::string str(std::uint64_t n) { return std::to_string(n); }

// Why the pixels of a parsed dataset cannot be whole, "" when they can. A dataset without
// pixels (SR, REG, RT structures) has nothing to check. Lengths come from the element headers,
// which the parse checked against the file: the pixels themselves are never loaded.
std::string pixelProblem(DcmDataset& ds) {
  DcmElement* px = nullptr;
  const char* name = "Pixel Data";
  if (ds.findAndGetElement(DCM_PixelData, px).bad()) {
    px = nullptr;
    if (ds.findAndGetElement(DCM_FloatPixelData, px).good())
      name = "Float Pixel Data";
    else if (ds.findAndGetElement(DCM_DoubleFloatPixelData, px).good())
      name = "Double Float Pixel Data";
    else
      return {};
  }
  Uint16 rows = 0, columns = 0, bits = 0, samples = 1;
  ds.findAndGetUint16(DCM_Rows, rows);
  ds.findAndGetUint16(DCM_Columns, columns);
  ds.findAndGetUint16(DCM_BitsAllocated, bits);
  if (ds.findAndGetUint16(DCM_SamplesPerPixel, samples).bad()) samples = 1;
  if (rows == 0 || columns == 0 || bits == 0 || samples == 0)
    return std::string("its ") + name + " comes without Rows, Columns, Samples per Pixel and " +
           "Bits Allocated";
  Sint32 frames = 1;
  OFString framesText;
  if (ds.findAndGetOFString(DCM_NumberOfFrames, framesText).good() && !framesText.empty()) {
    if (ds.findAndGetSint32(DCM_NumberOfFrames, frames).bad() || frames < 1)
      return "its Number of Frames is '" + std::string(framesText.c_str()) + "'";
  }
  const DcmXfer xfer(ds.getOriginalXfer());
  if (xfer.isEncapsulated() && px->getLengthField() == DCM_UndefinedLength) {
    DcmPixelSequence* seq = nullptr;
    const DcmRepresentationParameter* none = nullptr;
    if (px->ident() != EVR_PixelData ||
        OFstatic_cast(DcmPixelData*, px)
            ->getEncapsulatedRepresentation(ds.getOriginalXfer(), none, seq)
            .bad() ||
        seq == nullptr || seq->card() == 0)
      return "its encapsulated Pixel Data holds no items";
    // Item 0 is the Basic Offset Table; every frame needs a fragment of its own at least.
    const std::uint64_t fragments = seq->card() - 1;
    if (fragments < static_cast<std::uint64_t>(frames))
      return "its encapsulated Pixel Data holds " +
             mvw::countOf(static_cast<long long>(fragments), "fragment") + " for " +
             mvw::countOf(static_cast<long long>(frames), "frame");
    DcmPixelItem* table = nullptr;
    if (seq->getItem(table, 0).bad() || table == nullptr)
      return "its Basic Offset Table is missing";
    const Uint32 tableLength = table->getLength();
    if (tableLength == 0) return {};
    if (tableLength != 4u * static_cast<Uint32>(frames))
      return "its Basic Offset Table has " + str(tableLength / 4) + " entries for " +
             str(static_cast<std::uint64_t>(frames)) + " frames";
    // Each offset (from the first fragment's item tag) must be where a fragment starts.
    std::set<std::uint64_t> starts;
    std::uint64_t at = 0;
    for (unsigned long i = 1; i < seq->card(); ++i) {
      DcmPixelItem* item = nullptr;
      if (seq->getItem(item, i).bad() || item == nullptr) return "a fragment cannot be read";
      starts.insert(at);
      at += 8u + item->getLength();
    }
    Uint8* bytes = nullptr;
    if (table->getUint8Array(bytes).bad() || bytes == nullptr)
      return "its Basic Offset Table cannot be read";
    for (Sint32 f = 0; f < frames; ++f) {
      const Uint8* b = bytes + 4 * f;
      const std::uint64_t offset =
          b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<std::uint64_t>(b[3]) << 24);
      if (!starts.count(offset))
        return "its Basic Offset Table points frame " + str(static_cast<std::uint64_t>(f) + 1) +
               " at byte " + str(offset) + ", where no fragment starts";
    }
    return {};
  }
  // Native: the values of every frame, bit-packed for Bits Allocated 1 (a SEG), padded to even.
  OFString photometric;
  ds.findAndGetOFString(DCM_PhotometricInterpretation, photometric);
  const std::uint64_t perPixel = io::storedSamplesPerPixel(samples, photometric.c_str());
  const std::uint64_t needed = io::nativePixelDataBytes(
      rows, columns, static_cast<std::uint64_t>(frames), samples, bits, photometric.c_str());
  const std::uint64_t holds = px->getLengthField();
  if (holds == DCM_UndefinedLength)
    return std::string("its ") + name + " is encapsulated in a native transfer syntax (" +
           xfer.getXferName() + ")";
  if (holds < needed)
    return std::string("its ") + name + " holds " + str(holds) + " bytes where " + str(rows) +
           " rows x " + str(columns) + " columns x " + str(static_cast<std::uint64_t>(frames)) +
           " frames x " + str(perPixel) + " samples x " + str(bits) + " bits need " +
           (needed == std::numeric_limits<std::uint64_t>::max() ? std::string("more than 2^64")
                                                                : str(needed + (needed & 1)));
  return {};
}

}  // namespace

std::optional<FileUids> readUids(const fs::path& file) {
  DcmFileFormat ff;
  if (loadWhole(ff, file).bad()) return std::nullopt;
  return uidsOf(*ff.getDataset());
}

InstanceCheck checkInstance(const fs::path& file) {
  InstanceCheck check;
  DcmFileFormat ff;
  if (const OFCondition c = loadWhole(ff, file); c.bad()) {
    check.problem = std::string("it does not parse as DICOM (") + c.text() + ")";
    return check;
  }
  check.uids = uidsOf(*ff.getDataset());
  if (!check.uids)
    check.problem = "it carries no SOP Instance UID";
  else
    check.problem = pixelProblem(*ff.getDataset());
  return check;
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
  const InstanceCheck check = checkInstance(file);
  const std::optional<FileUids>& uids = check.uids;
  auto refuse = [&](const std::string& why) {
    fs::remove(file, ec);
    throw ServiceError(server_.text + ": sent " + why);
  };
  if (!uids) refuse("an object that is not a DICOM file with a SOP Instance UID: " + check.problem);
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
  // Checked after the UID, so the message names the instance: a server fault (exit 3).
  if (!check.problem.empty())
    refuse("instance " + uids->sopInstance + ", which is not whole: " + check.problem);
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
  const int n =
      std::fprintf(stderr, "pacs: %s, %.1f MB, %.1f MB/s%s",
                   mvw::countOf(static_cast<long long>(received_.size()), "instance").c_str(), mb,
                   s > 0 ? mb / s : 0.0, final ? "\n" : "\r");
  lineOpen_ = !final;
  lineLength_ = n > 0 ? static_cast<std::size_t>(n) : 0;
  std::fflush(stderr);
}

void Receiver::clearLine() {
  if (!lineOpen_) return;
  std::fprintf(stderr, "%s\r", std::string(lineLength_, ' ').c_str());
  std::fflush(stderr);
  lineOpen_ = false;
}

Transfer Receiver::transfer() const {
  Transfer t;
  t.instances = static_cast<int>(received_.size());
  t.bytes = bytes_;
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return t;
}

}  // namespace mvw::pacs::detail
