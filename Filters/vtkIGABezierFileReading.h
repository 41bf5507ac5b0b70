/**
 * @class   vtkIGABezierFileReading
 * @brief   Reads a VTK XML unstructured grid of Bézier hexahedra and quadrilaterals into Kernels
 *          patches, refusing what VTK's reader would crash or abort on, with one message naming
 *          the file.
 *
 * VTK's vtkXMLUnstructuredGridReader aborts the process when a piece claims more points or
 * cells than it can allocate, and prints its errors over several lines. Read() first scans the
 * header (by hand: a regex recurses per character and a megabyte-long attribute would overflow
 * the stack) and refuses pieces claiming more than `memoryLimitBytes`, binary arrays (inline or
 * appended, raw or base64) whose headers claim more than their data holds (VTK allocates a
 * compressed array's table of blocks and each compressed block as the header says), and cell
 * offsets ending past the connectivity or the memory (VTK allocates the connectivity the last
 * offset gives and aborts when it cannot; IGAXMLArrays.h). The tags in the first MiB of a file
 * are checked, all of a text's. Then it reads with VTK's
 * messages collected (the first is returned in the error or as a warning), catches what the
 * reader throws, and converts the grid with vtkIGABezierHexahedra. igaview and the .vtu fuzz
 * target read through it; RunQuietly serves any pipeline request the same way.
 */
#ifndef vtkIGABezierFileReading_h
#define vtkIGABezierFileReading_h

#include "IGAViewFiltersModule.h"  // for export macro
#include "vtkIGABezierHexahedra.h" // for Patches
#include "vtkSmartPointer.h"       // for return value

#include <functional> // for RunQuietly
#include <string>
#include <vector>

class vtkUnstructuredGrid;

class IGAVIEWFILTERS_EXPORT vtkIGABezierFileReading
{
public:
  /// Reads `name`, a file, or `text` when given (the file's contents; `name` then names it in
  /// messages). Returns the grid, or null with `error` set (starting with 'NAME'); non-fatal
  /// notes go to `warnings`. `memoryLimitBytes` 0: this machine's physical memory.
  static vtkSmartPointer<vtkUnstructuredGrid> Read(const std::string& name, const std::string* text,
    vtkIGABezierHexahedra::Patches& patches, std::string& error, std::vector<std::string>& warnings,
    double memoryLimitBytes = 0);

  /// Runs `request` (a pipeline update, returning whether it succeeded) with VTK's messages
  /// collected rather than printed (several lines each, repeated by VTK's log). `message`: the
  /// first one's text, without the file, line and object VTK puts before it, or what `request`
  /// threw (then false).
  static bool RunQuietly(const std::function<bool()>& request, std::string& message);
};

#endif
