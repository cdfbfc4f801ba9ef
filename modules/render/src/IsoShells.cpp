#include "IsoShells.h"

#include <algorithm>
#include <cstring>

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>

namespace mvw::render::detail {

ShellMesh extractShell(const std::vector<float>& values, glm::ivec3 dims,
                       const glm::dmat4& worldFromIndex, double threshold) {
  // Padded by one voxel of "nothing" (far below any threshold) so that every shell closes at
  // the volume's box: outside the box the emission is zero, as the paper's background is.
  const glm::ivec3 pd = dims + 2;
  std::vector<float> padded(static_cast<std::size_t>(pd.x) * pd.y * pd.z, -1.0e6f);
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      std::copy_n(values.data() + (static_cast<std::size_t>(k) * dims.y + j) * dims.x, dims.x,
                  padded.data() + (static_cast<std::size_t>(k + 1) * pd.y + (j + 1)) * pd.x + 1);
  vtkNew<vtkImageData> image;  // padded index space: unit spacing, origin at index -1
  image->SetDimensions(pd.x, pd.y, pd.z);
  image->SetOrigin(-1.0, -1.0, -1.0);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetArray(padded.data(), static_cast<vtkIdType>(padded.size()), 1);  // no copy
  image->GetPointData()->SetScalars(scalars);
  vtkNew<vtkFlyingEdges3D> edges;
  edges->SetInputData(image);
  edges->SetValue(0, threshold);
  edges->ComputeNormalsOn();
  edges->ComputeGradientsOff();
  edges->ComputeScalarsOff();
  edges->Update();
  vtkPolyData* poly = edges->GetOutput();
  ShellMesh mesh;
  mesh.threshold = threshold;
  const vtkIdType n = poly->GetNumberOfPoints();
  vtkDataArray* normals = poly->GetPointData()->GetNormals();
  // Normals of an affine map transform with the inverse transpose of its linear part.
  const glm::dmat3 linear(worldFromIndex);
  const glm::dmat3 normalMatrix = glm::inverseTranspose(linear);
  mesh.vertices.resize(static_cast<std::size_t>(n) * 6);
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    poly->GetPoint(i, p);
    const glm::dvec3 w = glm::dvec3(worldFromIndex * glm::dvec4(p[0], p[1], p[2], 1.0));
    glm::dvec3 nrm(0.0, 0.0, 1.0);
    if (normals) {
      double t[3];
      normals->GetTuple(i, t);
      // Flying edges' normals point down the gradient (toward lower values): outward.
      const glm::dvec3 m = normalMatrix * glm::dvec3(t[0], t[1], t[2]);
      if (glm::length(m) > 0) nrm = glm::normalize(m);
    }
    float* out = &mesh.vertices[static_cast<std::size_t>(i) * 6];
    out[0] = float(w.x), out[1] = float(w.y), out[2] = float(w.z);
    out[3] = float(nrm.x), out[4] = float(nrm.y), out[5] = float(nrm.z);
  }
  vtkCellArray* polys = poly->GetPolys();
  mesh.indices.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()) * 3);
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
    if (npts == 3)
      for (int k = 0; k < 3; ++k) mesh.indices.push_back(static_cast<unsigned>(pts[k]));
  return mesh;
}

}  // namespace mvw::render::detail
