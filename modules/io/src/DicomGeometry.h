#pragma once
// Where the voxels of a DICOM series lie: the geometry tags read safely, the patient matrix,
// and the slices put in place (positioned slices, the frames of a multi-frame file, a Siemens
// mosaic, slices with no position), with the notes that say what was assumed (internal to
// mvw_io: vtk-dicom types stay inside this folder).
#include <filesystem>
#include <optional>
#include <utility>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"

class vtkDICOMMetaData;
class vtkDICOMReader;
class vtkDICOMValue;
class vtkImageData;

namespace mvw::io::detail {

// A DS value of `count` numbers, each a whole decimal string and at most `limit` in size
// ("nan", "1e999" and text are not: vtk-dicom would read them as 0 or inf; a position beyond
// 1 km is no place in a scanner).
bool numbersOk(const vtkDICOMValue& value, unsigned int count, double limit = 1e6);

// The row and column directions of an ImageOrientationPatient of six numbers, as stored (not
// normalised); nullopt when it is not six numbers.
std::optional<std::pair<glm::dvec3, glm::dvec3>> orientationAxes(const vtkDICOMValue& iop);

// The reader's patient matrix (LPS) times the data's origin and spacing: worldFromIndex of
// the stack as vtk-dicom decoded it.
glm::dmat4 patientWorldFromIndex(vtkDICOMReader* reader, vtkImageData* image);
// The same from the data's origin and spacing (the reader's output information).
glm::dmat4 patientWorldFromIndex(vtkDICOMReader* reader, const double origin[3],
                                 const double spacing[3]);

// The decoded stack with every slice where its header puts it: the frames of a single
// (`singleFile`) multi-frame file without per-frame positions stacked along the slice normal,
// a single Siemens mosaic unpacked, slices without any position stacked in instance order, and
// positioned slices placed by placeSlices (SliceGeometry.h; `first` names the file).
Volume arrangeSlices(Volume volume, vtkDICOMReader* reader, bool singleFile,
                     const ReadOptions& options, const std::filesystem::path& first);

// Notes for the geometry the reader replaced: no or an unusable ImageOrientationPatient (axes
// assumed LPS) or PixelSpacing (the in-plane voxel size assumed).
void noteGeometryFallbacks(Volume& volume, vtkDICOMMetaData* meta);

}  // namespace mvw::io::detail
