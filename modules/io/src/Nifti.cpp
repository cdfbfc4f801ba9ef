// NIfTI-1/2 through vtkNIFTIImageReader/Writer, behind a header check of our own: the
// header's dimensions, datatype and offset are checked against the file (or the length of
// the decompressed stream) and the memory limit before VTK allocates anything.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <zlib.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>

#include "FileChecks.h"
#include "Formats.h"
#include "VtkBridge.h"
#include "VtkMessages.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/io/VtkImageView.h"

namespace mvw::io::detail {

namespace {

namespace fs = std::filesystem;

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Reads a file that may be gzip-compressed (zlib reads plain files transparently).
class GzFile {
 public:
  explicit GzFile(const fs::path& path) : path_(path), f_(gzopen(path.c_str(), "rb")) {
    if (!f_) throw InputError(path, "cannot open the file");
  }
  ~GzFile() { gzclose(f_); }
  GzFile(const GzFile&) = delete;
  GzFile& operator=(const GzFile&) = delete;

  // Reads up to n bytes; throws on a corrupt stream, returns fewer at a (possibly early) end.
  std::size_t read(void* dst, std::size_t n) {
    std::size_t got = 0;
    while (got < n) {
      const unsigned chunk = static_cast<unsigned>(std::min<std::size_t>(n - got, 1u << 30));
      const int r = gzread(f_, static_cast<char*>(dst) + got, chunk);
      if (r < 0) {
        int code = 0;
        const char* msg = gzerror(f_, &code);
        throw InputError(path_, std::string("corrupt compressed data: ") + (msg ? msg : "?"));
      }
      if (r == 0) break;
      got += static_cast<std::size_t>(r);
    }
    // zlib reports a truncated gzip stream only through gzerror after the last read.
    int code = Z_OK;
    std::string msg = gzerror(f_, &code);
    if (code != Z_OK && code != Z_STREAM_END) {
      if (msg.rfind(path_.string() + ": ", 0) == 0) msg = msg.substr(path_.string().size() + 2);
      throw InputError(path_, "corrupt or truncated compressed data: " + msg);
    }
    return got;
  }

  // Counts the bytes left, up to `limit`, without keeping them.
  std::uintmax_t skipCount(std::uintmax_t limit) {
    std::array<char, 1 << 16> buf;
    std::uintmax_t total = 0;
    while (total < limit) {
      const std::size_t r = read(buf.data(), std::min<std::uintmax_t>(buf.size(), limit - total));
      if (r == 0) break;
      total += r;
    }
    return total;
  }

 private:
  fs::path path_;
  gzFile f_;
};

struct NiftiHeaderFacts {
  int version = 1;  // 0: Analyze 7.5 (no magic)
  bool singleFile = true;
  std::array<long long, 8> dim{};
  int datatype = 0;
  int bitpix = 0;
  long long voxOffset = 0;
  double pixdim[4] = {0, 0, 0, 0};
  std::uintmax_t consumed = 0;  // bytes of the stream parseHeader has read
};

template <class T>
T load(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

// Bytes per value and number of interleaved channels for the datatypes mvw reads.
bool datatypeLayout(int datatype, int* bytes, int* channels) {
  *channels = 1;
  switch (datatype) {
    case 2:
    case 256:
      *bytes = 1;
      return true;  // uint8, int8
    case 4:
    case 512:
      *bytes = 2;
      return true;  // int16, uint16
    case 8:
    case 768:
    case 16:
      *bytes = 4;
      return true;  // int32, uint32, float32
    case 64:
      *bytes = 8;
      return true;  // float64
    case 128:
      *bytes = 1;
      *channels = 3;
      return true;  // RGB24
    case 2304:
      *bytes = 1;
      *channels = 4;
      return true;  // RGBA32
    default:
      return false;
  }
}

NiftiHeaderFacts parseHeader(const fs::path& path, GzFile& file) {
  unsigned char h[540] = {};
  const std::size_t got = file.read(h, sizeof h);
  if (got < 348)
    throw InputError(path, "file too short for a NIfTI header (" + std::to_string(got) + " bytes)");
  NiftiHeaderFacts f;
  f.consumed = got;
  const int size = load<int>(h, false);
  const bool swap = !(size == 348 || size == 540);
  const int sizeofHdr = load<int>(h, swap);
  if (sizeofHdr == 348) {
    if (std::memcmp(h + 344, "n+1\0", 4) == 0)
      f.version = 1;
    else if (std::memcmp(h + 344, "ni1\0", 4) == 0) {
      f.version = 1;
      f.singleFile = false;
    } else {
      f.version = 0;
      f.singleFile = false;
    }
    for (int i = 0; i < 8; ++i) f.dim[i] = load<short>(h + 40 + 2 * i, swap);
    f.datatype = load<short>(h + 70, swap);
    f.bitpix = load<short>(h + 72, swap);
    for (int i = 0; i < 4; ++i) f.pixdim[i] = load<float>(h + 76 + 4 * i, swap);
    const float off = load<float>(h + 108, swap);
    if (!std::isfinite(off) || off < 0 || off > 1e9)
      throw InputError(path, "invalid vox_offset in the NIfTI header");
    f.voxOffset = static_cast<long long>(off);
  } else if (sizeofHdr == 540) {
    if (got < 540) throw InputError(path, "file too short for a NIfTI-2 header");
    if (std::memcmp(h + 4, "n+2\0", 4) == 0)
      f.version = 2;
    else if (std::memcmp(h + 4, "ni2\0", 4) == 0) {
      f.version = 2;
      f.singleFile = false;
    } else
      throw InputError(path, "NIfTI-2 header without a valid magic string");
    f.datatype = load<short>(h + 12, swap);
    f.bitpix = load<short>(h + 14, swap);
    for (int i = 0; i < 8; ++i) f.dim[i] = load<long long>(h + 16 + 8 * i, swap);
    for (int i = 0; i < 4; ++i) f.pixdim[i] = load<double>(h + 104 + 8 * i, swap);
    f.voxOffset = load<long long>(h + 168, swap);
  } else {
    throw InputError(path, "not a NIfTI file (header size field is " + std::to_string(size) + ")");
  }
  if (f.dim[0] < 1 || f.dim[0] > 7)
    throw InputError(path, "invalid dim[0] = " + std::to_string(f.dim[0]) + " in the NIfTI header");
  for (int i = 1; i <= f.dim[0]; ++i)
    if (f.dim[i] < 1)
      throw InputError(path, "invalid dim[" + std::to_string(i) +
                                 "] = " + std::to_string(f.dim[i]) + " in the NIfTI header");
  for (int i = static_cast<int>(f.dim[0]) + 1; i < 8; ++i) f.dim[i] = 1;
  for (int i = 1; i <= 3; ++i)
    if (f.dim[i] > (1 << 24))
      throw InputError(
          path, "implausible dimension " + std::to_string(f.dim[i]) + " in the NIfTI header");
  int bytes = 0, channels = 0;
  if (!datatypeLayout(f.datatype, &bytes, &channels))
    throw InputError(path, "unsupported NIfTI datatype " + std::to_string(f.datatype));
  if (f.bitpix != bytes * channels * 8)
    throw InputError(path, "bitpix " + std::to_string(f.bitpix) + " does not match datatype " +
                               std::to_string(f.datatype));
  if (f.singleFile && f.voxOffset < sizeofHdr)
    throw InputError(path, "vox_offset " + std::to_string(f.voxOffset) + " lies inside the header");
  return f;
}

// The file that holds the voxels: the .nii itself, or the .img beside a .hdr.
fs::path imagePathFor(const fs::path& path, const NiftiHeaderFacts& facts) {
  if (facts.singleFile) return path;
  std::string s = path.string();
  const bool gz = endsWith(s, ".gz");
  if (gz) s.resize(s.size() - 3);
  if (!endsWith(s, ".hdr"))
    throw InputError(path, "two-file NIfTI/Analyze header must end in .hdr");
  s.replace(s.size() - 4, 4, ".img");
  if (gz && fs::exists(s + ".gz")) return s + ".gz";
  return s;
}

vtkNew<vtkMatrix4x4> toVtk(const glm::dmat4& m) {
  vtkNew<vtkMatrix4x4> v;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) v->SetElement(r, c, m[c][r]);
  return v;
}

glm::dmat4 fromVtk(vtkMatrix4x4* v) {
  glm::dmat4 m(1.0);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[c][r] = v->GetElement(r, c);
  return m;
}

const glm::dmat4 kLpsFromRas = glm::dmat4(glm::dvec4(-1, 0, 0, 0), glm::dvec4(0, -1, 0, 0),
                                          glm::dvec4(0, 0, 1, 0), glm::dvec4(0, 0, 0, 1));

// Checks the header and counts the (decompressed) bytes that are really there, against the
// file and options.maxBytes, before VTK allocates anything.
NiftiHeaderFacts checkNiftiFile(const fs::path& path, const ReadOptions& options) {
  GzFile file(path);
  const NiftiHeaderFacts facts = parseHeader(path, file);
  int bytes = 0, channels = 0;
  datatypeLayout(facts.datatype, &bytes, &channels);
  long long components = channels;
  for (int i = 4; i < 8; ++i) components *= facts.dim[i];
  const glm::ivec3 dims{static_cast<int>(facts.dim[1]), static_cast<int>(facts.dim[2]),
                        static_cast<int>(facts.dim[3])};
  const std::size_t dataBytes =
      checkedVolumeBytes(path, dims, components, static_cast<std::size_t>(bytes), options.maxBytes);
  const fs::path image = imagePathFor(path, facts);
  const std::uintmax_t need = dataBytes + static_cast<std::uintmax_t>(facts.voxOffset);
  std::uintmax_t have = 0;
  if (facts.singleFile) {
    have = facts.consumed + file.skipCount(need > facts.consumed ? need - facts.consumed : 0);
  } else {
    companionFileSize(path, image);
    GzFile img(image);
    have = img.skipCount(need);
  }
  if (have < need)
    throw InputError(path,
                     (facts.singleFile ? std::string("file") : "its image file " + image.string()) +
                         " is truncated: header and image data need " + std::to_string(need) +
                         " bytes, the file holds " + std::to_string(have));
  return facts;
}

// Millimetres per spatial unit of the header's xyzt_units: 1 metre, 2 mm, 3 micron (0:
// unknown, mm assumed).
double unitScaleOf(vtkNIFTIImageHeader* header) {
  switch (header->GetXYZTUnits() & 7) {
    case 1:
      return 1000.0;
    case 3:
      return 0.001;
    default:
      return 1.0;
  }
}

// The sform where it is a usable geometry, else the qform, else the identity (axes toward R,
// A, S), with notes; `fromSform` says whether the sform was taken.
glm::dmat4 rasFromDataOf(const fs::path& path, vtkNIFTIImageReader* reader,
                         std::vector<std::string>& notes, bool& fromSform) {
  vtkNIFTIImageHeader* header = reader->GetNIFTIHeader();
  glm::dmat4 rasFromData(1.0);
  // A matrix that maps the voxel axes to three independent finite directions: an sform of
  // zeros, NaN or two equal rows (a broken writer) is no geometry.
  auto usable = [](const glm::dmat4& m) {
    return detail::geometryProblem(m) == detail::GeometryProblem::None;
  };
  const bool hasSform = header->GetSFormCode() > 0 && reader->GetSFormMatrix();
  const bool hasQform = header->GetQFormCode() > 0 && reader->GetQFormMatrix();
  bool sformBroken = false;
  if (hasSform && !usable(fromVtk(reader->GetSFormMatrix()))) {
    if (!hasQform || !usable(fromVtk(reader->GetQFormMatrix())))
      throw InputError(path, std::string("the sform (srow_x, srow_y, srow_z) is not a usable "
                                         "geometry (non-finite or singular)") +
                                 (hasQform ? ", nor is the qform" : " and there is no qform"));
    sformBroken = true;
    notes.push_back(
        "the sform is not a usable geometry (non-finite or singular): the qform is "
        "used instead");
  }
  if (hasSform && !sformBroken) {
    rasFromData = fromVtk(reader->GetSFormMatrix());
  } else if (hasQform) {
    if (!usable(fromVtk(reader->GetQFormMatrix())))
      throw InputError(path,
                       "the qform (quatern_b/c/d, qoffset_x/y/z) is not a usable geometry "
                       "(non-finite or singular)");
    // The qform takes its voxel size from pixdim (VTK would quietly put 1 for a zero).
    for (int a = 1; a <= 3; ++a)
      if (!(std::abs(header->GetPixDim(a)) > 0) || !std::isfinite(header->GetPixDim(a)))
        throw InputError(path, "invalid voxel size pixdim[" + std::to_string(a) +
                                   "] = " + std::to_string(header->GetPixDim(a)) + " with a qform");
    rasFromData = fromVtk(reader->GetQFormMatrix());
  } else {
    notes.push_back("no qform or sform in the header: axes assumed to point toward R, A, S");
  }
  fromSform = hasSform && !sformBroken;
  return rasFromData;
}

// worldFromIndex (LPS mm) from the reader's origin, spacing and the header's sform or qform,
// with notes on the units, dimensions beyond time, the geometry chosen and zero voxel sizes.
glm::dmat4 niftiWorldFromIndex(const fs::path& path, vtkNIFTIImageReader* reader,
                               const NiftiHeaderFacts& facts, Volume& volume) {
  vtkImageData* image = reader->GetOutput();
  double origin[3], spacing[3];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  vtkNIFTIImageHeader* header = reader->GetNIFTIHeader();
  const double unitScale = unitScaleOf(header);
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(spacing[a]) || spacing[a] <= 0)
      throw InputError(path, "invalid voxel size pixdim[" + std::to_string(a + 1) +
                                 "] = " + std::to_string(spacing[a]));
  }
  auto& notes = volume.metadata().notes;
  if (const int code = header->GetXYZTUnits() & 7; code >= 4)
    notes.push_back("xyzt_units spatial code " + std::to_string(code) +
                    " is no unit (1 metre, 2 mm, 3 micron): millimetres assumed");
  // Beyond time (dim[4]): a 5-D image (vectors, tensors, several statistics per voxel) or
  // more. Its values become frames like time points, said so.
  if (facts.dim[5] > 1 || facts.dim[6] > 1 || facts.dim[7] > 1) {
    std::string sizes;
    for (int i = 4; i < 8; ++i)
      sizes += (i > 4 ? " x " : "") + std::to_string(std::max<long long>(1, facts.dim[i]));
    notes.push_back("dimensions 4 to 7 (" + sizes + ") are read as " +
                    std::to_string(volume.components()) +
                    " frames in storage order: the frame of a study is one of these");
  }
  bool fromSform = false;
  const glm::dmat4 rasFromData = rasFromDataOf(path, reader, notes, fromSform);
  // A zero pixdim is no voxel size: say which one was used instead (VTK puts 1 for a zero).
  for (int a = 1; a <= 3; ++a) {
    if (std::abs(header->GetPixDim(a)) > 0 || std::isnan(header->GetPixDim(a))) continue;
    const double used =
        fromSform ? glm::length(glm::dvec3(rasFromData[a - 1])) * spacing[a - 1] : spacing[a - 1];
    char size[32];
    std::snprintf(size, sizeof size, "%g", used * unitScale);
    notes.push_back("pixdim[" + std::to_string(a) +
                    "] is 0: " + (fromSform ? "the sform's voxel size " : std::string("")) + size +
                    " mm assumed along axis " + std::to_string(a));
  }
  glm::dmat4 dataFromIndex(1.0);
  for (int a = 0; a < 3; ++a) {
    dataFromIndex[a][a] = spacing[a];
    dataFromIndex[3][a] = origin[a];
  }
  glm::dmat4 unit(unitScale);
  unit[3][3] = 1.0;
  return kLpsFromRas * unit * rasFromData * dataFromIndex;
}

// As nifti_clib reads them: a slope of 0 (or not a number) means no scaling; an intercept
// that is not a number is 0 beside a real slope (said, not dropped with the slope).
void applyNiftiRescale(Volume& volume, vtkNIFTIImageReader* reader) {
  auto& notes = volume.metadata().notes;
  const double slope = reader->GetRescaleSlope();
  double intercept = reader->GetRescaleIntercept();
  if (slope != 0.0 && std::isfinite(slope) && !std::isfinite(intercept)) {
    notes.push_back("scl_inter " + shortNumber(intercept) +
                    " is not a number: read as 0 beside scl_slope " + shortNumber(slope));
    intercept = 0.0;
  }
  if (slope != 0.0 && std::isfinite(slope) && (slope != 1.0 || intercept != 0.0)) {
    volume = volume.converted(ScalarType::Float32, slope, intercept);  // keeps the metadata
    volume.metadata().notes.push_back("scl_slope " + shortNumber(slope) + ", scl_inter " +
                                      shortNumber(intercept) + " applied (values as float32)");
  } else if (!std::isfinite(slope)) {
    notes.push_back("scl_slope " + shortNumber(slope) + " is not a number: values used as stored");
  }
}

// A statistic map says so in its intent code: its values are the statistic, named as the unit
// (the attribute window of an fMRI statistic map starts from it: study/ModalityDefaults).
std::string intentUnit(int intentCode) {
  switch (intentCode) {
    case 2:
      return "r";  // NIFTI_INTENT_CORREL
    case 3:
      return "t";  // NIFTI_INTENT_TTEST
    case 4:
      return "F";  // NIFTI_INTENT_FTEST
    case 5:
      return "z";  // NIFTI_INTENT_ZSCORE
    default:
      return "";
  }
}

}  // namespace

Volume readNifti(const fs::path& path, const ReadOptions& options) {
  regularFileSize(path);
  const NiftiHeaderFacts facts = checkNiftiFile(path, options);

  VtkMessageScope messages;
  vtkNew<vtkNIFTIImageReader> reader;
  reader->SetFileName(path.c_str());
  reader->TimeAsVectorOn();
  reader->Update();
  if (!messages.firstError().empty() || reader->GetErrorCode() != 0)
    throw InputError(path, "NIfTI reader failed: " + messages.firstError());
  Volume volume = volumeFromImage(reader->GetOutput(), path);
  volume.setWorldFromIndex(niftiWorldFromIndex(path, reader, facts, volume));
  if (reader->GetQFac() < 0)
    volume.metadata().notes.push_back(
        "qfac = -1: slice order reversed to a right-handed index frame");
  applyNiftiRescale(volume, reader);

  auto& meta = volume.metadata();
  meta.format = facts.version == 2 ? "NIfTI-2" : facts.version == 1 ? "NIfTI-1" : "Analyze 7.5";
  meta.sourcePath = path.string();
  vtkNIFTIImageHeader* header = reader->GetNIFTIHeader();
  if (const char* d = header->GetDescrip(); d && *d) meta.seriesDescription = d;
  if (const std::string unit = intentUnit(header->GetIntentCode()); !unit.empty()) meta.unit = unit;
  return volume;
}

void writeNifti(const Volume& input, const fs::path& path) {
  // NIfTI readers (VTK's included) want a right-handed index frame; a left-handed volume is
  // written with its slice order reversed, which keeps every voxel at its world position.
  const glm::dmat4& w = input.worldFromIndex();
  const bool leftHanded = glm::determinant(glm::dmat3(w)) < 0;
  Volume flipped;
  const Volume* volume = &input;
  if (leftHanded) {
    const glm::ivec3 d = input.dimensions();
    flipped = Volume(d, input.components(), input.scalarType(), w);
    const std::size_t slice =
        static_cast<std::size_t>(d.x) * d.y * input.components() * scalarSize(input.scalarType());
    for (int k = 0; k < d.z; ++k)
      std::memcpy(flipped.data() + slice * k, input.data() + slice * (d.z - 1 - k), slice);
    glm::dmat4 m = w;
    m[3] = w * glm::dvec4(0, 0, d.z - 1, 1);
    m[2] = -w[2];
    flipped.setWorldFromIndex(m);
    volume = &flipped;
  }
  auto image = io::imageViewOfVolume(*volume);  // no copy of the voxels: writers only read
  const glm::dvec3 spacing = volume->spacing();
  image->SetSpacing(spacing.x, spacing.y, spacing.z);
  glm::dmat4 ras = kLpsFromRas * volume->worldFromIndex();
  for (int c = 0; c < 3; ++c) ras[c] /= spacing[c];  // VTK factors pixdim out of the matrix
  auto matrix = toVtk(ras);

  writeAtomically(path, [&](const fs::path& tmp) {
    VtkMessageScope messages;
    vtkNew<vtkNIFTIImageWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(tmp.c_str());
    // VTK leaves xyzt_units 0 (unknown) unless a header says otherwise: say millimetres, so
    // nibabel, FSL and 3D Slicer need not guess.
    vtkNew<vtkNIFTIImageHeader> header;
    header->SetXYZTUnits(vtkNIFTIImageHeader::UnitsMM | vtkNIFTIImageHeader::UnitsSec);
    writer->SetNIFTIHeader(header);
    writer->SetQFormMatrix(matrix);
    writer->SetSFormMatrix(matrix);
    if (volume->components() > 1 && volume->scalarType() != ScalarType::UInt8)
      writer->SetTimeDimension(volume->components());
    if (!volume->metadata().seriesDescription.empty())
      writer->SetDescription(volume->metadata().seriesDescription.substr(0, 79).c_str());
    writer->Write();
    if (!messages.firstError().empty() || writer->GetErrorCode() != 0)
      throw Error(path.string() + ": NIfTI writer failed: " + messages.firstError());
  });
}

}  // namespace mvw::io::detail
