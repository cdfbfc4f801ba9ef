#include "mvw/resampling/Transform.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>

#include "mvw/core/Error.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::resampling {

namespace {

// glm is column-major (m[col][row]); rotation matrices read better written by rows.
glm::dmat3 fromRows(double a00, double a01, double a02, double a10, double a11, double a12,
                    double a20, double a21, double a22) {
  return glm::dmat3(a00, a10, a20, a01, a11, a21, a02, a12, a22);
}

glm::dmat3 rotationX(double a, bool derivative) {
  const double c = std::cos(a), s = std::sin(a);
  if (derivative) return fromRows(0, 0, 0, 0, -s, -c, 0, c, -s);
  return fromRows(1, 0, 0, 0, c, -s, 0, s, c);
}
glm::dmat3 rotationY(double a, bool derivative) {
  const double c = std::cos(a), s = std::sin(a);
  if (derivative) return fromRows(-s, 0, c, 0, 0, 0, -c, 0, -s);
  return fromRows(c, 0, s, 0, 1, 0, -s, 0, c);
}
glm::dmat3 rotationZ(double a, bool derivative) {
  const double c = std::cos(a), s = std::sin(a);
  if (derivative) return fromRows(-s, -c, 0, c, -s, 0, 0, 0, 0);
  return fromRows(c, -s, 0, s, c, 0, 0, 0, 1);
}

glm::dmat4 affine(const glm::dmat3& linear, const glm::dvec3& offset) {
  glm::dmat4 m(linear);
  m[3] = glm::dvec4(offset, 1.0);
  return m;
}

// ITK's MatrixOffsetTransformBase: y = A (x - c) + c + t, so offset = t + c - A c.
glm::dmat4 itkMatrix(const glm::dmat3& a, const glm::dvec3& translation, const glm::dvec3& centre) {
  return affine(a, translation + centre - a * centre);
}

bool allFinite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

std::vector<double> parseNumbers(const std::string& text, const std::filesystem::path& path,
                                 const std::string& key) {
  std::vector<double> values;
  std::istringstream in(text);
  std::string token;
  while (in >> token) {
    // strtod, not stream extraction: it accepts what ITK writes for large and tiny values.
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0')
      throw InputError(path, key + " holds a value that is not a number: '" + token + "'");
    if (!std::isfinite(v)) throw InputError(path, key + " holds a value that is not finite");
    values.push_back(v);
  }
  return values;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

}  // namespace

glm::dmat3 eulerRotation(const glm::dvec3& angles) {
  return rotationZ(angles.z, false) * rotationX(angles.x, false) * rotationY(angles.y, false);
}

glm::dmat3 eulerRotationDerivative(const glm::dvec3& angles, int axis) {
  return rotationZ(angles.z, axis == 2) * rotationX(angles.x, axis == 0) *
         rotationY(angles.y, axis == 1);
}

glm::dmat4 rigidMatrix(const RigidParameters& parameters, const glm::dvec3& centre) {
  return itkMatrix(eulerRotation(parameters.angles), parameters.translation, centre);
}

RigidParameters rigidParameters(const glm::dmat4& rigid, const glm::dvec3& centre) {
  // R = Rz Rx Ry gives R[2][1] = sin(ax), R[2][0] = -cos(ax) sin(ay), R[2][2] = cos(ax) cos(ay),
  // R[0][1] = -sin(az) cos(ax), R[1][1] = cos(az) cos(ax) (row, column): ITK's decomposition.
  const glm::dmat3 r(rigid);
  auto at = [&](int row, int col) { return r[col][row]; };
  RigidParameters p;
  p.angles.x = std::asin(std::clamp(at(2, 1), -1.0, 1.0));
  if (std::abs(std::cos(p.angles.x)) > 1e-12) {
    p.angles.y = std::atan2(-at(2, 0), at(2, 2));
    p.angles.z = std::atan2(-at(0, 1), at(1, 1));
  } else {
    // Gimbal lock: only az + ay (or az - ay) is defined; put it all in az.
    p.angles.y = 0.0;
    p.angles.z = std::atan2(at(1, 0), at(0, 0));
  }
  const glm::dvec3 offset(rigid[3]);
  p.translation = offset - centre + r * centre;
  return p;
}

Transform::Transform(const glm::dmat4& fixedFromMoving, const glm::dvec3& centre)
    : fixedFromMoving_(fixedFromMoving),
      movingFromFixed_(glm::inverse(fixedFromMoving)),
      centre_(centre) {}

Transform Transform::fromMovingFromFixed(const glm::dmat4& movingFromFixed,
                                         const glm::dvec3& centre) {
  Transform t;
  t.movingFromFixed_ = movingFromFixed;
  t.fixedFromMoving_ = glm::inverse(movingFromFixed);
  t.centre_ = centre;
  return t;
}

glm::dvec3 Transform::fixedFromMovingPoint(const glm::dvec3& moving) const {
  return glm::dvec3(fixedFromMoving_ * glm::dvec4(moving, 1.0));
}

glm::dvec3 Transform::movingFromFixedPoint(const glm::dvec3& fixed) const {
  return glm::dvec3(movingFromFixed_ * glm::dvec4(fixed, 1.0));
}

bool Transform::isRigid(double tolerance) const {
  const glm::dmat3 r(fixedFromMoving_);
  const glm::dmat3 e = glm::transpose(r) * r - glm::dmat3(1.0);
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row)
      if (std::abs(e[c][row]) > tolerance) return false;
  return std::abs(glm::determinant(r) - 1.0) <= tolerance && fixedFromMoving_[0][3] == 0.0 &&
         fixedFromMoving_[1][3] == 0.0 && fixedFromMoving_[2][3] == 0.0;
}

void Transform::writeItk(const std::filesystem::path& path) const {
  const glm::dmat3 a(movingFromFixed_);
  const glm::dvec3 offset(movingFromFixed_[3]);
  const glm::dvec3 translation = offset - centre_ + a * centre_;
  std::ostringstream text;
  text.precision(17);
  text << "#Insight Transform File V1.0\n#Transform 0\n"
       << "Transform: AffineTransform_double_3_3\nParameters:";
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      text << ' ' << a[col][row] + 0.0;  // ITK: row-major; + 0.0: no "-0"
  for (int i = 0; i < 3; ++i) text << ' ' << translation[i] + 0.0;
  text << "\nFixedParameters: " << centre_.x + 0.0 << ' ' << centre_.y + 0.0 << ' '
       << centre_.z + 0.0 << "\n";

  try {
    io::writeTextAtomically(path, text.str());
  } catch (const Error&) {
    throw Error(path.string() + ": cannot write the transform file");
  }
}

Transform Transform::readItk(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "no such file");
  if (std::filesystem::file_size(path, ec) > (1u << 20))
    throw InputError(path, "too large for an ITK text transform file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the file");

  std::string line, type;
  std::vector<double> parameters, fixed;
  bool sawHeader = false, sawParameters = false, sawFixed = false;
  int transforms = 0;
  while (std::getline(in, line)) {
    line = trim(line);
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (line.rfind("#Insight Transform File", 0) == 0) sawHeader = true;
      continue;
    }
    const auto colon = line.find(':');
    if (colon == std::string::npos) throw InputError(path, "unexpected line '" + line + "'");
    const std::string key = trim(line.substr(0, colon));
    const std::string value = trim(line.substr(colon + 1));
    if (key == "Transform") {
      ++transforms;
      type = value;
    } else if (key == "Parameters") {
      parameters = parseNumbers(value, path, key);
      sawParameters = true;
    } else if (key == "FixedParameters") {
      fixed = parseNumbers(value, path, key);
      sawFixed = true;
    } else {
      throw InputError(path, "unknown key '" + key + "'");
    }
  }
  if (!sawHeader)
    throw InputError(path, "not an ITK transform file (no '#Insight Transform File' line)");
  if (transforms != 1)
    throw InputError(path, "holds " + std::to_string(transforms) +
                               " transforms; mvw reads files with exactly one");
  if (!sawParameters || !sawFixed)
    throw InputError(path, "'" + type + "' lacks Parameters or FixedParameters");

  auto is = [&](const char* name) {
    return type == std::string(name) + "_double_3_3" || type == std::string(name) + "_float_3_3";
  };
  auto expect = [&](std::size_t nParameters, std::size_t minFixed, std::size_t maxFixed) {
    if (parameters.size() != nParameters)
      throw InputError(path, type + " needs " + std::to_string(nParameters) +
                                 " Parameters, the file has " + std::to_string(parameters.size()));
    if (fixed.size() < minFixed || fixed.size() > maxFixed)
      throw InputError(path, type + " has " + std::to_string(fixed.size()) +
                                 " FixedParameters, expected " + std::to_string(minFixed));
  };
  auto centreOf = [&]() {
    return fixed.size() >= 3 ? glm::dvec3(fixed[0], fixed[1], fixed[2]) : glm::dvec3(0.0);
  };

  glm::dmat4 movingFromFixed(1.0);
  glm::dvec3 centre(0.0);
  if (is("AffineTransform") || is("MatrixOffsetTransformBase")) {
    expect(12, 3, 3);
    glm::dmat3 a;
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col)
        a[col][row] = parameters[static_cast<std::size_t>(row * 3 + col)];
    centre = centreOf();
    movingFromFixed = itkMatrix(a, {parameters[9], parameters[10], parameters[11]}, centre);
  } else if (is("Euler3DTransform")) {
    // ITK 4 writes the centre; ITK 5 adds a fourth value, ComputeZYX (R = Rz Ry Rx when 1).
    expect(6, 3, 4);
    centre = centreOf();
    const glm::dvec3 angles(parameters[0], parameters[1], parameters[2]);
    const bool zyx = fixed.size() == 4 && fixed[3] != 0.0;
    const glm::dmat3 r =
        zyx ? rotationZ(angles.z, false) * rotationY(angles.y, false) * rotationX(angles.x, false)
            : eulerRotation(angles);
    movingFromFixed = itkMatrix(r, {parameters[3], parameters[4], parameters[5]}, centre);
  } else if (is("VersorRigid3DTransform")) {
    expect(6, 3, 3);
    centre = centreOf();
    const double x = parameters[0], y = parameters[1], z = parameters[2];
    const double n2 = x * x + y * y + z * z;
    if (n2 > 1.0) throw InputError(path, "versor has a norm above 1");
    const double w = std::sqrt(1.0 - n2);
    const glm::dmat3 r =
        fromRows(1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
                 2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                 2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y));
    movingFromFixed = itkMatrix(r, {parameters[3], parameters[4], parameters[5]}, centre);
  } else if (is("TranslationTransform")) {
    expect(3, 0, 0);
    movingFromFixed = affine(glm::dmat3(1.0), {parameters[0], parameters[1], parameters[2]});
  } else {
    throw InputError(path, "unsupported transform type '" + type +
                               "' (mvw reads 3-D Affine, MatrixOffsetTransformBase, Euler3D, "
                               "VersorRigid3D and Translation transforms)");
  }
  const double det = glm::determinant(glm::dmat3(movingFromFixed));
  if (!allFinite(movingFromFixed) || !std::isfinite(det) || std::abs(det) < 1e-9)
    throw InputError(path, "the transform matrix is singular");
  return fromMovingFromFixed(movingFromFixed, centre);
}

}  // namespace mvw::resampling
