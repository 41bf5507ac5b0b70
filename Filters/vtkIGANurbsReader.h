/**
 * @class   vtkIGANurbsReader
 * @brief   Base of the NURBS file readers: parses FileName into a vtkIGANurbsData and puts out its
 *          Bézier cells.
 *
 * The output is a vtkUnstructuredGrid of VTK_BEZIER_HEXAHEDRON / VTK_BEZIER_QUADRILATERAL cells
 * with the NURBS description in field and cell data (see vtkIGANurbsData). The file is parsed
 * once per change of FileName or of the file's modification time. The G+Smo and GeoPDEs files
 * read so far hold one state of the geometry, so no time steps are advertised; ParaView makes a
 * numbered series of files a time series by wrapping the readers in vtkFileSeriesReader (the
 * plugin's reader proxies do).
 *
 * Problems with the file are reported once, by vtkErrorMacro, as "FILE:LINE: problem" (LINE is
 * left out where the file as a whole is at fault), and RequestData then returns 0; so is a
 * file whose Bézier cells would need more memory than MemoryLimitMB. Subclasses implement
 * ReadNurbs().
 */
#ifndef vtkIGANurbsReader_h
#define vtkIGANurbsReader_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkNew.h"               // for vtkNew
#include "vtkUnstructuredGridAlgorithm.h"

#include <iosfwd> // for std::istream
#include <string> // for the parse state

class vtkIGANurbsData;

class IGAVIEWFILTERS_EXPORT vtkIGANurbsReader : public vtkUnstructuredGridAlgorithm
{
public:
  vtkTypeMacro(vtkIGANurbsReader, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Most memory, in MiB, that the Bézier cells of one time step may take while they are built
  /// (a few kilobytes of high-degree NURBS can expand to gigabytes of cells); a file needing
  /// more is refused with the size it would need, and so is a file larger than this (it is read
  /// whole before it is parsed). 0, the default: half the machine's memory.
  vtkSetClampMacro(MemoryLimitMB, double, 0, VTK_DOUBLE_MAX);
  vtkGetMacro(MemoryLimitMB, double);
  ///@}

  ///@{
  /// Exact "parameter_u/v/w" on patches whose weights vary, by cells one degree higher
  /// (vtkIGANurbsData::ExactParameters); off by default.
  vtkSetMacro(ExactParameters, bool);
  vtkGetMacro(ExactParameters, bool);
  vtkBooleanMacro(ExactParameters, bool);
  ///@}

  /// 1 when the start of `name` is in this reader's format, else 0. ParaView's reader factory
  /// asks it to tell G+Smo XML from other XML and GeoPDEs text from other text.
  int CanReadFile(const char* name);

  /// The patches read (empty until the reader has been updated or when the file is bad).
  vtkIGANurbsData* GetNurbsData();

protected:
  vtkIGANurbsReader();
  ~vtkIGANurbsReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Reads `text`, the contents of FileName, into `data`. Returns "" or the problem as
  /// "LINE: problem" (or just "problem" for the file as a whole).
  virtual std::string ReadNurbs(const std::string& text, vtkIGANurbsData* data) = 0;
  /// Whether the first 64 KiB of a file are in this reader's format.
  virtual bool IsOwnFormat(const std::string& head) const = 0;
  /// What, besides FileName, its modification time and MemoryLimitMB, a parse depends on
  /// (further files and their modification times): the file is parsed again when it changes.
  virtual std::string InputStamp() const { return std::string(); }

  char* FileName = nullptr;
  double MemoryLimitMB = 0;

private:
  vtkIGANurbsReader(const vtkIGANurbsReader&) = delete;
  void operator=(const vtkIGANurbsReader&) = delete;

  /// ReadNurbs on the stream's contents, with what it throws turned into its problem.
  std::string ReadGuarded(std::istream& in);
  /// MemoryLimitMB in bytes, or half the machine's memory when it is 0.
  double MemoryLimitBytes() const;
  /// "" when the Bézier cells of a step fit MemoryLimitMB, else why not.
  std::string MemoryProblem() const;
  /// "" when the file, which is read whole before it is parsed, fits MemoryLimitMB.
  std::string FileSizeProblem(const std::string& file) const;

  vtkNew<vtkIGANurbsData> Data;
  bool ExactParameters = false;
  std::string Error;      // of the last parse, empty when it succeeded
  std::string ParsedFile; // FileName and modification time of the last parse
};

#endif
