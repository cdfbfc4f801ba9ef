#include "SiemensMosaic.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>

#include "SiemensCsa.h"

namespace mvw::io::detail {

namespace {

std::string mm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

Volume keptWithNote(Volume mosaic, const std::string& why) {
  const glm::ivec3 d = mosaic.dimensions();
  mosaic.metadata().notes.push_back("Siemens MOSAIC not unpacked (" + why + "): kept as one " +
                                    std::to_string(d.x) + " x " + std::to_string(d.y) + " image");
  return mosaic;
}

}  // namespace

Volume unpackMosaic(Volume mosaic, const std::uint8_t* csa, std::size_t csaSize,
                    double spacingBetweenSlices, double sliceThickness) {
  const glm::ivec3 d = mosaic.dimensions();
  if (d.z != 1) return keptWithNote(std::move(mosaic), "more than one image");
  std::string why;
  const auto header = CsaHeader::parse(csa, csaSize, &why);
  if (!header) return keptWithNote(std::move(mosaic), "CSA header: " + why);
  const auto count = header->number("NumberOfImagesInMosaic");
  if (!count || *count < 1 || *count > 4096 || *count != std::floor(*count))
    return keptWithNote(std::move(mosaic), "no usable NumberOfImagesInMosaic in the CSA header");
  const int images = static_cast<int>(*count);
  const int perSide = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(images))));
  if (d.x % perSide != 0 || d.y % perSide != 0)
    return keptWithNote(std::move(mosaic), std::to_string(images) + " tiles do not divide a " +
                                               std::to_string(d.x) + " x " + std::to_string(d.y) +
                                               " image");
  const int tx = d.x / perSide, ty = d.y / perSide;

  const glm::dmat4& w = mosaic.worldFromIndex();
  const glm::dvec3 alongI(w[0]), alongJ(w[1]);  // world step per voxel along i (a row) and j
  glm::dvec3 normal = glm::cross(glm::normalize(alongI), glm::normalize(alongJ));
  bool reversed = false;
  if (header->items("SliceNormalVector").size() == 3) {
    glm::dvec3 csaNormal(0.0);
    for (int a = 0; a < 3; ++a)
      csaNormal[a] = header->number("SliceNormalVector", static_cast<std::size_t>(a)).value_or(0);
    const double len = glm::length(csaNormal);
    const double cosine = len > 0 ? glm::dot(csaNormal / len, normal) : 0.0;
    if (std::abs(cosine) < 0.99)
      return keptWithNote(std::move(mosaic),
                          "CSA SliceNormalVector is not the normal of ImageOrientationPatient");
    reversed = cosine < 0;  // tiles run against row x column
  }
  double step = spacingBetweenSlices;
  std::string stepFrom = "SpacingBetweenSlices";
  if (!(step > 0.0 && std::isfinite(step))) {
    step = sliceThickness;
    stepFrom = "SliceThickness (no SpacingBetweenSlices)";
  }
  if (!(step > 0.0 && std::isfinite(step)))
    return keptWithNote(std::move(mosaic), "neither SpacingBetweenSlices nor SliceThickness");

  // The mosaic's ImagePositionPatient is the corner of the whole mosaic placed as if it were
  // one tile-sized image centred on the acquisition: move it to the first tile's corner.
  const glm::dvec3 corner =
      glm::dvec3(w[3]) + alongI * ((d.x - tx) / 2.0) + alongJ * ((d.y - ty) / 2.0);
  // Tile k is acquired at corner + k * step * (CSA normal). Slices are stored so that the
  // index frame stays right-handed (k along row x column), as every other reader does.
  glm::dmat4 m = w;
  m[2] = glm::dvec4(normal * step, 0.0);
  m[3] = glm::dvec4(reversed ? corner - normal * (step * (images - 1)) : corner, 1.0);
  Volume out({tx, ty, images}, mosaic.components(), mosaic.scalarType(), m);
  out.metadata() = mosaic.metadata();
  const std::size_t pixel = scalarSize(mosaic.scalarType()) * mosaic.components();
  for (int k = 0; k < images; ++k) {
    const int tile = reversed ? images - 1 - k : k;
    const int x0 = (tile % perSide) * tx, y0 = (tile / perSide) * ty;
    for (int y = 0; y < ty; ++y)
      std::memcpy(out.data() + (static_cast<std::size_t>(k) * ty + y) * tx * pixel,
                  mosaic.data() + (static_cast<std::size_t>(y0 + y) * d.x + x0) * pixel,
                  static_cast<std::size_t>(tx) * pixel);
  }
  out.metadata().notes.push_back(
      "Siemens MOSAIC unpacked: " + std::to_string(images) + " tiles of " + std::to_string(tx) +
      " x " + std::to_string(ty) + " from the CSA header, stacked " + mm(step) + " mm apart (" +
      stepFrom + ")" +
      (reversed ? ", in reverse tile order (the CSA slice normal runs against row x column)" : ""));
  out.metadata().sliceSpacing = SliceSpacing{images, step, step, step, true, false};
  return out;
}

}  // namespace mvw::io::detail
