#pragma once
// The files of a DICOM series and the stack vtk-dicom reads from them: each file's pixel-data
// size checked against the file, the files that are not slices of the main stack left out,
// the largest stack chosen, and the slices it stacks checked for positions and one
// orientation (internal to mvw_io: vtk-dicom types stay inside this folder).
#include <filesystem>
#include <string>

#include <vtkSmartPointer.h>

class vtkDICOMMetaData;
class vtkDICOMReader;
class vtkStringArray;

namespace mvw::io::detail {

// Refuses files whose header claims more pixel data than the file holds (uncompressed: a
// compressed stream's length says nothing about the decoded size) and, compressed, files with
// a frame whose own header does not match Rows, Columns, SamplesPerPixel or BitsAllocated
// (FrameHeaders.h), before any decoder runs.
void checkPixelDataSizes(vtkDICOMMetaData* meta, vtkStringArray* files);

// The files of a series (one frame each) that are not slices of its main stack: those of
// another orientation than the most common one (a localizer or a reformat filed under the
// acquisition's series), and, where others have a position, those without a usable one (a
// position of text or NaN would be read as 0, its slice put at the origin). They are left out
// before vtk-dicom sorts, so its stacks are not split at them; the gap a left-out slice leaves
// is found and filled like any missing slice. Returns the note ("" when all are kept); `kept`
// then holds the other files.
std::string leaveOutStrayFiles(vtkDICOMReader* reader, vtkStringArray* files,
                               vtkSmartPointer<vtkStringArray>& kept);

// vtk-dicom splits a series into stacks when its files do not line up (a file of another
// orientation, one without a position, a second location per slice) and reads the first
// stack, which can be a handful of an acquisition's slices. The largest stack is read instead
// (the first of equals), and the note says which files were left out ("" for one stack).
std::string chooseLargestStack(vtkDICOMReader* reader, vtkStringArray* files);

// Every slice the reader will stack: a position of three numbers when any slice has one, and
// one orientation. Slices of different orientations (a three-plane localizer, a reformat
// filed under the acquisition's series) are not one volume; a position that is not numbers
// would be read as 0 and place its slice at the origin. InputError naming `path`.
void checkSliceGeometry(vtkDICOMReader* reader, vtkStringArray* files,
                        const std::filesystem::path& path);

}  // namespace mvw::io::detail
