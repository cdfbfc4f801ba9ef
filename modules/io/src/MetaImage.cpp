// MetaImage (.mha with the data inline, .mhd with a separate data file), read and written by
// hand: the format is a short text header, and VTK's reader ignores its TransformMatrix.
// World coordinates are LPS as in ITK. TransformMatrix lists the i, j and k axis directions
// one after another, as ITK's MetaImageIO writes it.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <zlib.h>

#include "FileChecks.h"
#include "Formats.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::io::detail {

namespace {

namespace fs = std::filesystem;

const std::map<std::string, ScalarType> kElementTypes = {
    {"MET_UCHAR", ScalarType::UInt8},   {"MET_CHAR", ScalarType::Int8},
    {"MET_USHORT", ScalarType::UInt16}, {"MET_SHORT", ScalarType::Int16},
    {"MET_UINT", ScalarType::UInt32},   {"MET_INT", ScalarType::Int32},
    {"MET_FLOAT", ScalarType::Float32}, {"MET_DOUBLE", ScalarType::Float64}};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<double> numbers(const fs::path& path, const std::string& key, const std::string& text,
                            std::size_t count) {
  std::istringstream in(text);
  std::vector<double> v;
  for (std::string word; in >> word;) {
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0')
      throw InputError(path, key + " holds '" + word + "', which is not a number");
    if (!std::isfinite(x))
      throw InputError(path, key + " holds " + word + ", a value that is not finite");
    v.push_back(x);
  }
  if (v.size() != count)
    throw InputError(path, key + " must hold " + std::to_string(count) + " numbers, not " +
                               std::to_string(v.size()) + " ('" + text + "')");
  return v;
}

// MetaIO's own rule: a value starting with T, t or 1 is true ("True", "TRUE", "T", "1").
bool isTrue(const std::string& v) {
  return !v.empty() && (v[0] == 'T' || v[0] == 't' || v[0] == '1');
}

// The header's fields up to ElementDataFile (the last one: the data may follow it in the
// same file, at dataOffset).
struct MetaHeader {
  std::map<std::string, std::string> fields;
  std::uintmax_t dataOffset = 0;

  std::string get(const std::string& key) const {
    auto it = fields.find(key);
    return it == fields.end() ? std::string() : it->second;
  }
};

MetaHeader readMetaHeader(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the file");
  MetaHeader header;
  std::string line;
  bool sawDataFile = false;
  while (std::getline(in, line)) {
    if (static_cast<long long>(in.tellg()) > (1 << 16))
      throw InputError(path, "no ElementDataFile in the first 64 KiB: not a MetaImage header");
    const auto eq = line.find('=');
    if (eq == std::string::npos) {
      if (trim(line).empty()) continue;
      throw InputError(path, "header line without '=': '" + trim(line).substr(0, 60) + "'");
    }
    const std::string key = trim(line.substr(0, eq));
    if (!header.fields.emplace(key, trim(line.substr(eq + 1))).second)
      throw InputError(path, "the header gives " + key + " twice");
    if (key == "ElementDataFile") {
      sawDataFile = true;
      header.dataOffset = static_cast<std::uintmax_t>(in.tellg());
      break;
    }
  }
  if (!sawDataFile) throw InputError(path, "MetaImage header has no ElementDataFile line");
  return header;
}

// worldFromIndex from ElementSpacing (or ElementSize), Offset (or Origin, Position) and
// TransformMatrix (or Rotation, Orientation) over `ndims` axes.
glm::dmat4 metaWorldFromIndex(const fs::path& path, const MetaHeader& header, int ndims) {
  auto get = [&](const std::string& key) { return header.get(key); };
  glm::dvec3 spacing(1.0), origin(0.0);
  glm::dmat3 direction(1.0);
  std::string spacingKey = !get("ElementSpacing").empty() ? "ElementSpacing" : "ElementSize";
  if (!get(spacingKey).empty()) {
    const auto s = numbers(path, spacingKey, get(spacingKey), ndims);
    for (int a = 0; a < ndims; ++a) {
      if (!(s[a] > 0)) throw InputError(path, spacingKey + " must be positive");
      spacing[a] = s[a];
    }
  }
  for (const char* key : {"Offset", "Origin", "Position"}) {
    if (get(key).empty()) continue;
    const auto o = numbers(path, key, get(key), ndims);
    for (int a = 0; a < ndims; ++a) origin[a] = o[a];
    break;
  }
  for (const char* key : {"TransformMatrix", "Rotation", "Orientation"}) {
    if (get(key).empty()) continue;
    const auto m = numbers(path, key, get(key), static_cast<std::size_t>(ndims * ndims));
    for (int c = 0; c < ndims; ++c)
      for (int r = 0; r < ndims; ++r) direction[c][r] = m[c * ndims + r];
    if (std::abs(glm::determinant(direction)) < 1e-6)
      throw InputError(path, std::string(key) + " is singular");
    break;
  }
  return makeWorldFromIndex(origin, spacing, direction);
}

// The `bytes` of image data into volume.data(): from the header's own file (LOCAL, whose
// size is fileSize) or the data file beside it, after HeaderSize, zlib-compressed or raw, in
// the byte order the header gives.
void readMetaData(const fs::path& path, const MetaHeader& header, std::uintmax_t fileSize,
                  std::size_t bytes, Volume& volume) {
  auto get = [&](const std::string& key) { return header.get(key); };
  const std::string dataFile = get("ElementDataFile");
  fs::path dataPath = path;
  std::uintmax_t offset = header.dataOffset;
  if (dataFile == "LIST")
    throw InputError(path, "ElementDataFile = LIST (one file per slice) is not supported");
  if (dataFile != "LOCAL") {
    dataPath = path.parent_path() / dataFile;
    offset = 0;
  }
  const std::uintmax_t dataFileSize =
      dataFile == "LOCAL" ? fileSize : companionFileSize(path, dataPath);
  if (!get("HeaderSize").empty()) {
    const long long h = std::atoll(get("HeaderSize").c_str());
    if (h == -1)
      offset = dataFileSize >= bytes ? dataFileSize - bytes : 0;
    else if (h >= 0)
      offset += static_cast<std::uintmax_t>(h);
    else
      throw InputError(path, "invalid HeaderSize");
  }
  if (offset > dataFileSize)
    throw InputError(dataPath, "data offset lies past the end of the file");
  std::ifstream data(dataPath, std::ios::binary);
  data.seekg(static_cast<std::streamoff>(offset));
  if (isTrue(get("CompressedData"))) {
    const std::uintmax_t compressed = dataFileSize - offset;
    std::vector<unsigned char> packed(compressed);
    data.read(reinterpret_cast<char*>(packed.data()), static_cast<std::streamsize>(compressed));
    z_stream z{};
    if (inflateInit(&z) != Z_OK) throw Error("zlib inflateInit failed");
    z.next_in = packed.data();
    z.avail_in = static_cast<uInt>(std::min<std::uintmax_t>(compressed, UINT32_MAX));
    z.next_out = reinterpret_cast<Bytef*>(volume.data());
    z.avail_out = static_cast<uInt>(bytes);
    const int rc = inflate(&z, Z_FINISH);
    const std::size_t produced = bytes - z.avail_out;
    inflateEnd(&z);
    if (rc != Z_STREAM_END && !(rc == Z_BUF_ERROR && produced == bytes))
      throw InputError(dataPath, produced < bytes
                                     ? "compressed image data is truncated or corrupt (" +
                                           std::to_string(produced) + " of " +
                                           std::to_string(bytes) + " bytes)"
                                     : "compressed image data is corrupt");
  } else {
    if (dataFileSize - offset < bytes)
      throw InputError(dataPath, "file is truncated: the header needs " + std::to_string(bytes) +
                                     " bytes of image data, the file has " +
                                     std::to_string(dataFileSize - offset));
    data.read(reinterpret_cast<char*>(volume.data()), static_cast<std::streamsize>(bytes));
    if (!data) throw InputError(dataPath, "read error");
  }
  const std::string msb = !get("ElementByteOrderMSB").empty() ? get("ElementByteOrderMSB")
                                                              : get("BinaryDataByteOrderMSB");
  const ScalarType type = volume.scalarType();
  if (isTrue(msb) && scalarSize(type) > 1) {
    const std::size_t w = scalarSize(type);
    for (std::size_t i = 0; i < bytes; i += w)
      std::reverse(volume.data() + i, volume.data() + i + w);
  }
}

}  // namespace

Volume readMetaImage(const fs::path& path, const ReadOptions& options) {
  const std::uintmax_t fileSize = regularFileSize(path);
  const MetaHeader header = readMetaHeader(path);
  auto get = [&](const std::string& key) { return header.get(key); };
  if (get("ObjectType") != "" && get("ObjectType") != "Image")
    throw InputError(path, "ObjectType is '" + get("ObjectType") + "', not Image");
  const std::string ndimsText = get("NDims");
  const int ndims = ndimsText.empty() ? 0 : std::atoi(ndimsText.c_str());
  if (ndims != 2 && ndims != 3)
    throw InputError(path, "NDims must be 2 or 3, not '" + ndimsText + "'");
  const auto dimSize = numbers(path, "DimSize", get("DimSize"), ndims);
  glm::ivec3 dims(1);
  for (int a = 0; a < ndims; ++a) {
    if (dimSize[a] < 1 || dimSize[a] > (1 << 24) || dimSize[a] != std::floor(dimSize[a]))
      throw InputError(path, "invalid DimSize value " + shortNumber(dimSize[a]));
    dims[a] = static_cast<int>(dimSize[a]);
  }
  if (!get("BinaryData").empty() && !isTrue(get("BinaryData")))
    throw InputError(path, "BinaryData = " + get("BinaryData") +
                               ": the voxels are text, and mvw reads binary MetaImage data only");
  const auto typeIt = kElementTypes.find(get("ElementType"));
  if (typeIt == kElementTypes.end())
    throw InputError(path, "unsupported ElementType '" + get("ElementType") + "'");
  const ScalarType type = typeIt->second;
  int channels = 1;
  if (!get("ElementNumberOfChannels").empty()) {
    channels = std::atoi(get("ElementNumberOfChannels").c_str());
    if (channels < 1 || channels > 64) throw InputError(path, "invalid ElementNumberOfChannels");
  }
  const glm::dmat4 worldFromIndex = metaWorldFromIndex(path, header, ndims);

  const std::size_t bytes =
      checkedVolumeBytes(path, dims, channels, scalarSize(type), options.maxBytes);
  Volume volume(dims, channels, type, worldFromIndex);
  readMetaData(path, header, fileSize, bytes, volume);
  auto& meta = volume.metadata();
  meta.format = "MetaImage";
  meta.sourcePath = path.string();
  if (!get("Modality").empty()) {
    const std::string m = get("Modality");  // MET_MOD_CT, MET_MOD_MR, MET_MOD_PET, ...
    meta.modality = m.rfind("MET_MOD_", 0) == 0 ? m.substr(8) : m;
    if (meta.modality == "PET") meta.modality = "PT";
  }
  return volume;
}

void writeMetaImage(const Volume& volume, const fs::path& path) {
  static const std::map<ScalarType, std::string> kNames = [] {
    std::map<ScalarType, std::string> m;
    for (const auto& [name, type] : kElementTypes) m[type] = name;
    return m;
  }();
  const bool detached = path.extension() == ".mhd";
  const fs::path rawPath = fs::path(path).replace_extension(".raw");
  std::ostringstream h;
  h.precision(17);
  const glm::ivec3 d = volume.dimensions();
  const glm::dvec3 s = volume.spacing(), o = volume.origin();
  const glm::dmat3 dir = volume.direction();
  h << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
    << "CompressedData = False\nTransformMatrix =";
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) h << ' ' << dir[c][r];
  h << "\nOffset = " << o.x << ' ' << o.y << ' ' << o.z << "\nCenterOfRotation = 0 0 0\n"
    << "ElementSpacing = " << s.x << ' ' << s.y << ' ' << s.z << "\nDimSize = " << d.x << ' ' << d.y
    << ' ' << d.z << "\n";
  if (volume.components() > 1) h << "ElementNumberOfChannels = " << volume.components() << "\n";
  h << "ElementType = " << kNames.at(volume.scalarType()) << "\n"
    << "ElementDataFile = " << (detached ? rawPath.filename().string() : "LOCAL") << "\n";
  auto writeBytes = [&](const fs::path& tmp, bool withHeader, bool withData) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (withHeader) out << h.str();
    if (withData)
      out.write(reinterpret_cast<const char*>(volume.data()),
                static_cast<std::streamsize>(volume.byteSize()));
    out.close();
    if (!out) throw Error(tmp.string() + ": write failed");
  };
  if (detached) {
    writeAtomically(rawPath, [&](const fs::path& tmp) { writeBytes(tmp, false, true); });
    writeAtomically(path, [&](const fs::path& tmp) { writeBytes(tmp, true, false); });
  } else {
    writeAtomically(path, [&](const fs::path& tmp) { writeBytes(tmp, true, true); });
  }
}

}  // namespace mvw::io::detail
