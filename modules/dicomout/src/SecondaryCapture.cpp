#include "mvw/dicomout/SecondaryCapture.h"

#include <cstdint>

#include "DcmCommon.h"
#include "mvw/core/Check.h"
#include "mvw/core/Error.h"
#include "mvw/core/Version.h"

namespace mvw::dicomout {

using namespace detail;

namespace {

// Source Image Sequence: the images the render was made from (at most this many are listed:
// a whole-body CT has thousands, and the series UID is in every item's study anyway).
constexpr std::size_t kMaxReferencedImages = 4096;

void putSourceImages(DcmDataset& ds, const DicomIdentity& source) {
  std::size_t n = 0;
  for (const SourceImage& image : source.images) {
    if (n++ == kMaxReferencedImages) break;
    DcmItem* item = nullptr;
    check(ds.findOrCreateSequenceItem(DCM_SourceImageSequence, item, -2), "Source Image Sequence");
    putString(*item, DCM_ReferencedSOPClassUID, image.sopClassUid);
    putString(*item, DCM_ReferencedSOPInstanceUID, image.sopInstanceUid);
  }
}

}  // namespace

void writeSecondaryCapture(const std::filesystem::path& file, const std::vector<Image>& frames,
                           const DicomIdentity& source, const SeriesInfo& series,
                           const CaptureInfo& info) {
  MVW_CHECK(!frames.empty());
  const int w = frames.front().width, h = frames.front().height;
  for (const Image& f : frames) MVW_CHECK(f.width == w && f.height == h);
  const bool multi = frames.size() > 1;
  DcmFileFormat ff;
  DcmDataset& ds = *ff.getDataset();
  putCommon(ds, source, series,
            multi ? UID_MultiframeTrueColorSecondaryCaptureImageStorage
                  : UID_SecondaryCaptureImageStorage,
            "OT");
  // SC Equipment: a workstation made it.
  putString(ds, DCM_ConversionType, "WSD");
  putString(ds, DCM_SecondaryCaptureDeviceManufacturer, "mvw");
  putString(ds, DCM_SecondaryCaptureDeviceManufacturerModelName, "mvw");
  putString(ds, DCM_SecondaryCaptureDeviceSoftwareVersions, kVersion);
  // General Image
  putString(ds, DCM_InstanceNumber, std::to_string(info.instanceNumber));
  putString(ds, DCM_PatientOrientation, "");
  putString(ds, DCM_ContentDate, today());
  putString(ds, DCM_ContentTime, nowTime());
  putString(ds, DCM_ImageType, "DERIVED\\SECONDARY");
  if (!info.derivation.empty())
    putString(ds, DCM_DerivationDescription, info.derivation.substr(0, 1024));
  putString(ds, DCM_BurnedInAnnotation, info.burnedInAnnotation ? "YES" : "NO");
  putSourceImages(ds, source);
  // Image Pixel: RGB, 8 bits, colour-by-pixel.
  check(ds.putAndInsertUint16(DCM_SamplesPerPixel, 3), "SamplesPerPixel");
  putString(ds, DCM_PhotometricInterpretation, "RGB");
  check(ds.putAndInsertUint16(DCM_PlanarConfiguration, 0), "PlanarConfiguration");
  check(ds.putAndInsertUint16(DCM_Rows, static_cast<Uint16>(h)), "Rows");
  check(ds.putAndInsertUint16(DCM_Columns, static_cast<Uint16>(w)), "Columns");
  check(ds.putAndInsertUint16(DCM_BitsAllocated, 8), "BitsAllocated");
  check(ds.putAndInsertUint16(DCM_BitsStored, 8), "BitsStored");
  check(ds.putAndInsertUint16(DCM_HighBit, 7), "HighBit");
  check(ds.putAndInsertUint16(DCM_PixelRepresentation, 0), "PixelRepresentation");
  if (multi) {
    // Multi-frame and Cine: the frames follow one another at the frame time.
    putString(ds, DCM_NumberOfFrames, std::to_string(frames.size()));
    check(ds.putAndInsertTagKey(DCM_FrameIncrementPointer, DCM_FrameTime), "FrameIncrementPointer");
    putString(ds, DCM_FrameTime, decimalString(info.frameTimeMs));
    if (info.frameTimeMs > 0)
      putString(ds, DCM_RecommendedDisplayFrameRate,
                std::to_string(static_cast<int>(1000.0 / info.frameTimeMs + 0.5)));
  }
  const std::size_t frameBytes = static_cast<std::size_t>(w) * h * 3;
  std::vector<Uint8> pixels(frameBytes * frames.size());
  std::size_t o = 0;
  for (const Image& f : frames)
    for (std::size_t p = 0; p < static_cast<std::size_t>(w) * h; ++p) {
      pixels[o++] = f.rgba[p * 4 + 0];
      pixels[o++] = f.rgba[p * 4 + 1];
      pixels[o++] = f.rgba[p * 4 + 2];
    }
  check(ds.putAndInsertUint8Array(DCM_PixelData, pixels.data(),
                                  static_cast<unsigned long>(pixels.size())),
        "PixelData");
  save(ff, file);
}

}  // namespace mvw::dicomout
