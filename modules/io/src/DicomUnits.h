#pragma once
// The values of a DICOM series in physical units: the rescale slope and intercept (applied
// here, per slice, where vtk-dicom's integer output would clip them), the dose grid scaling,
// and the unit each modality's values carry; PET goes on to SUV (DicomSuv.h) (internal to
// mvw_io: vtk-dicom types stay inside this folder).
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"

class vtkDICOMMetaData;
class vtkIntArray;

namespace mvw::io::detail {

// vtk-dicom keeps an integer output type when the slope and intercept are whole numbers, and
// clips what does not fit: a RescaleSlope of 1e6 on 12-bit data read as -32768 .. 32767
// without a word. True when a slice's slope (other than 1) could take its stored values (by
// BitsStored and PixelRepresentation) beyond the integer type vtk-dicom announces; the series
// is then read as stored and rescaled here, to float32 (rescaleSlices).
bool rescaleMayClip(vtkDICOMMetaData* meta, vtkIntArray* fileIndex, vtkIntArray* frameIndex,
                    int vtkType);

// The stored values of `volume` (read with AutoRescaleOff) times each slice's own slope plus
// its intercept, as float32. Slice k, component c comes from the file and frame the reader's
// index arrays name for slice k and time point c / samplesPerPixel.
Volume rescaleSlices(const Volume& volume, vtkDICOMMetaData* meta, vtkIntArray* fileIndex,
                     vtkIntArray* frameIndex, int samplesPerPixel);

// Notes on the rescale: applied here (`rescaledHere`), or a RescaleSlope that is not a usable
// factor and was not applied.
void noteRescale(Volume& volume, vtkDICOMMetaData* meta, bool rescaledHere);

// Sets metadata().unit by modality (CT: HU or RescaleType; RTDOSE: Gy or % with
// DoseGridScaling applied; PET: Bq/ml or SUVbw) with notes on what was not converted.
void fillUnitAndSuv(Volume& volume, vtkDICOMMetaData* meta, const ReadOptions& options);

}  // namespace mvw::io::detail
