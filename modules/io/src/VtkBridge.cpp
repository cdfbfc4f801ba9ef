#include "VtkBridge.h"

#include "mvw/io/VtkImageView.h"

#include <algorithm>
#include <cstring>

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkType.h>

#include "mvw/core/Error.h"

namespace mvw::io::detail {

namespace {

bool scalarTypeFromVtk(int vtkType, ScalarType* out) {
  switch (vtkType) {
    case VTK_UNSIGNED_CHAR:
      *out = ScalarType::UInt8;
      return true;
    case VTK_SIGNED_CHAR:
    case VTK_CHAR:
      *out = ScalarType::Int8;
      return true;
    case VTK_UNSIGNED_SHORT:
      *out = ScalarType::UInt16;
      return true;
    case VTK_SHORT:
      *out = ScalarType::Int16;
      return true;
    case VTK_UNSIGNED_INT:
      *out = ScalarType::UInt32;
      return true;
    case VTK_INT:
      *out = ScalarType::Int32;
      return true;
    case VTK_FLOAT:
      *out = ScalarType::Float32;
      return true;
    case VTK_DOUBLE:
      *out = ScalarType::Float64;
      return true;
    default:
      return false;
  }
}

int vtkTypeFromScalar(ScalarType type) {
  switch (type) {
    case ScalarType::UInt8:
      return VTK_UNSIGNED_CHAR;
    case ScalarType::Int8:
      return VTK_SIGNED_CHAR;
    case ScalarType::UInt16:
      return VTK_UNSIGNED_SHORT;
    case ScalarType::Int16:
      return VTK_SHORT;
    case ScalarType::UInt32:
      return VTK_UNSIGNED_INT;
    case ScalarType::Int32:
      return VTK_INT;
    case ScalarType::Float32:
      return VTK_FLOAT;
    case ScalarType::Float64:
      return VTK_DOUBLE;
  }
  return VTK_DOUBLE;
}

}  // namespace

VoxelLayout voxelLayout(vtkInformation* info) {
  int extent[6];
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  return {{extent[1] - extent[0] + 1, extent[3] - extent[2] + 1, extent[5] - extent[4] + 1},
          std::max(1, vtkImageData::GetNumberOfScalarComponents(info)),
          vtkImageData::GetScalarType(info)};
}

Volume volumeOfVtkType(glm::ivec3 dims, int components, int vtkType,
                       const std::filesystem::path& file) {
  ScalarType type;
  if (!scalarTypeFromVtk(vtkType, &type))
    throw InputError(file,
                     std::string("unsupported voxel type ") + vtkImageScalarTypeNameMacro(vtkType));
  if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0 || components <= 0)
    throw InputError(file, "no voxel data could be read");
  return Volume(dims, components, type, glm::dmat4(1.0));
}

Volume volumeFromImage(vtkImageData* image, const std::filesystem::path& file) {
  int dims[3];
  image->GetDimensions(dims);
  if (image->GetPointData()->GetScalars() == nullptr)
    throw InputError(file, "no voxel data could be read");
  Volume volume = volumeOfVtkType({dims[0], dims[1], dims[2]}, image->GetNumberOfScalarComponents(),
                                  image->GetScalarType(), file);
  std::memcpy(volume.data(), image->GetScalarPointer(), volume.byteSize());
  return volume;
}

}  // namespace mvw::io::detail

namespace mvw::io {

vtkSmartPointer<vtkImageData> imageViewOfVolume(const Volume& volume) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  const glm::ivec3 d = volume.dimensions();
  image->SetDimensions(d.x, d.y, d.z);
  vtkSmartPointer<vtkDataArray> array;
  array.TakeReference(
      vtkDataArray::CreateDataArray(detail::vtkTypeFromScalar(volume.scalarType())));
  array->SetNumberOfComponents(volume.components());
  // save = 1: VTK never frees or writes this memory; it belongs to the Volume.
  array->SetVoidArray(const_cast<std::byte*>(volume.data()),
                      static_cast<vtkIdType>(volume.valueCount()), 1);
  image->GetPointData()->SetScalars(array);
  return image;
}

}  // namespace mvw::io
