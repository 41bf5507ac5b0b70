#include "vtkIGABezierFileReading.h"

#include "IGAFileHead.h"

#include "vtkIGABezierHexahedra.h"

#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkStringOutputWindow.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <stdexcept>
#include <unistd.h>

namespace
{

/// "" or why the header's pieces claim more points or cells than `memory` bytes hold.
std::string claimedSizesProblem(const std::string& name, const std::string& head, double memory)
{
  // Bytes each point or cell needs at least: three coordinates; a connectivity entry, an
  // offset and a type.
  for (const auto& [key, bytes] : { std::pair<std::string, double>{ "NumberOfPoints=\"", 24.0 },
         std::pair<std::string, double>{ "NumberOfCells=\"", 17.0 } })
  {
    double claimed = 0;
    for (size_t at = head.find(key); at != std::string::npos; at = head.find(key, at + 1))
    {
      // strtod stops at the closing quote; the head ends in a NUL, so an open one stops too.
      claimed += std::strtod(head.c_str() + at + key.size(), nullptr);
    }
    if (!(claimed * bytes < memory))
    {
      char text[256];
      std::snprintf(text, sizeof text,
        "'%s' claims %.4g %s, which need at least %.3g GB, more than this machine's %.3g GB",
        name.c_str(), claimed, key[8] == 'P' ? "points" : "cells", claimed * bytes / 1e9,
        memory / 1e9);
      return text;
    }
  }
  return std::string();
}

/// The bytes of the base64 text at `at` (whitespace skipped) up to `count` of them.
std::string decodeBase64(const std::string& text, size_t at, size_t count)
{
  std::string bytes;
  unsigned bits = 0, value = 0;
  for (; at < text.size() && bytes.size() < count; ++at)
  {
    const char c = text[at];
    const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* digit = c ? std::strchr(alphabet, c) : nullptr;
    if (std::isspace(static_cast<unsigned char>(c)))
    {
      continue;
    }
    if (!digit)
    {
      break;
    }
    value = (value << 6) | unsigned(digit - alphabet);
    bits += 6;
    if (bits >= 8)
    {
      bits -= 8;
      bytes.push_back(char((value >> bits) & 0xff));
    }
  }
  return bytes;
}

/// Little-endian unsigned integers of `size` bytes each from `bytes`.
std::vector<double> words(const std::string& bytes, size_t size)
{
  std::vector<double> result;
  for (size_t at = 0; at + size <= bytes.size(); at += size)
  {
    double value = 0;
    for (size_t b = size; b-- > 0;)
    {
      value = value * 256 + double(static_cast<unsigned char>(bytes[at + b]));
    }
    result.push_back(value);
  }
  return result;
}

/// The value of attribute `key` (e.g. `Name="`) in the tag text, or "".
std::string attributeOf(const std::string& tag, const std::string& key)
{
  const size_t at = tag.find(key);
  if (at == std::string::npos)
  {
    return std::string();
  }
  const size_t begin = at + key.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

/// The bytes the data array whose tag holds `at` must decode to, when its piece says (its
/// points, point data, cell data, cell types and offsets), or -1 (connectivity, field data).
double expectedBytes(const std::string& text, size_t at)
{
  const size_t piece = text.rfind("<Piece", at), tagStart = text.rfind("<DataArray", at);
  if (piece == std::string::npos || tagStart == std::string::npos)
  {
    return -1;
  }
  size_t section = std::string::npos;
  std::string sectionTag;
  for (const char* tag : { "<Points", "<PointData", "<Cells", "<CellData", "<FieldData" })
  {
    const size_t found = text.rfind(tag, at);
    if (found != std::string::npos && found > piece &&
        (section == std::string::npos || found > section))
    {
      section = found;
      sectionTag = tag;
    }
  }
  const std::string pieceTag = text.substr(piece, text.find('>', piece) - piece);
  const std::string tag = text.substr(tagStart, text.find('>', tagStart) - tagStart);
  const std::string arrayName = attributeOf(tag, "Name=\"");
  double tuples = -1;
  if (sectionTag == "<Points" || sectionTag == "<PointData")
  {
    tuples = std::strtod(attributeOf(pieceTag, "NumberOfPoints=\"").c_str(), nullptr);
  }
  else if (sectionTag == "<CellData" ||
           (sectionTag == "<Cells" && (arrayName == "types" || arrayName == "offsets")))
  {
    tuples = std::strtod(attributeOf(pieceTag, "NumberOfCells=\"").c_str(), nullptr);
  }
  const std::string type = attributeOf(tag, "type=\"");
  const double size = type == "Int8" || type == "UInt8"                          ? 1
                      : type == "Int16" || type == "UInt16"                      ? 2
                      : type == "Int32" || type == "UInt32" || type == "Float32" ? 4
                      : type == "Int64" || type == "UInt64" || type == "Float64" ? 8
                                                                                 : -1;
  const std::string components = attributeOf(tag, "NumberOfComponents=\"");
  const double perTuple = components.empty() ? 1 : std::strtod(components.c_str(), nullptr);
  return tuples >= 0 && size > 0 ? tuples * perTuple * size : -1;
}

/// "'NAME': a binary data array's header claims WHAT of N bytes, THAN M".
std::string headerClaim(
  const std::string& name, const char* what, double claimed, const char* than, double held)
{
  char message[256];
  std::snprintf(message, sizeof message,
    "'%s': a binary data array's header claims %s of %.4g bytes, %s %.0f", name.c_str(), what,
    claimed, than, std::floor(held));
  return message;
}

/// "" or why a compressed array's header (base64 from `start`; its data `held` bytes at most;
/// the array `expected` bytes, or -1 when unknown) disagrees with its data or `memory`.
std::string compressedHeaderProblem(const std::string& name, const std::string& text, size_t start,
  double held, double expected, size_t word, double memory)
{
  const std::vector<double> head = words(decodeBase64(text, start, 3 * word), word);
  if (head.empty())
  {
    return std::string(); // no header: VTK's reader says so
  }
  const double blocks = head[0], blockSize = head.size() > 1 ? head[1] : 0,
               lastSize = head.size() > 2 ? head[2] : 0; // of a partial last block
  if (!(blockSize >= 1) || (blocks == 0 && lastSize != 0) || !(lastSize <= blockSize))
  {
    // VTK divides by the block size (a floating-point exception).
    return "'" + name + "': a binary data array's header gives inconsistent block sizes";
  }
  if (!((3 + blocks) * double(word) <= held))
  {
    return headerClaim(
      name, "a table of blocks", (3 + blocks) * double(word), "more than the data's", held);
  }
  const double total =
    blocks == 0 ? 0 : (blocks - 1) * blockSize + (lastSize > 0 ? lastSize : blockSize);
  if (!(total < memory))
  {
    return headerClaim(name, "uncompressed blocks", total, "more than the memory's", memory);
  }
  if (expected >= 0 && total != expected)
  {
    return headerClaim(name, "uncompressed blocks", total, "where the array holds", expected);
  }
  const std::vector<double> table =
    words(decodeBase64(text, start, (3 + size_t(blocks)) * word), word);
  double compressedBytes = 0;
  for (size_t b = 3; b < table.size(); ++b)
  {
    compressedBytes += table[b];
  }
  return compressedBytes <= held
           ? std::string()
           : headerClaim(name, "compressed blocks", compressedBytes, "more than the data's", held);
}

/// "" or why an inline binary array's header disagrees with its data: VTK allocates what the
/// header says (a compressed array's table of blocks, each compressed block, an uncompressed
/// array's byte count) and copies the blocks into the array as sized by the piece, so a header
/// claiming more than the data holds, more than `memory` or another size than the array's
/// overflows, crashes or allocates gigabytes.
std::string binaryHeaderProblem(const std::string& name, const std::string& text, double memory)
{
  const size_t word = text.find("header_type=\"UInt64\"") != std::string::npos ? 8 : 4;
  const bool compressed = text.find("compressor=\"") != std::string::npos;
  const std::string key = "format=\"binary\"";
  for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1))
  {
    const size_t start = text.find('>', at);
    if (start == std::string::npos)
    {
      break;
    }
    const size_t end = std::min(text.find('<', start), text.size());
    const double held = 0.75 * double(end - start); // decoded bytes at most
    const double expected = expectedBytes(text, at);
    std::string problem;
    if (compressed)
    {
      problem = compressedHeaderProblem(name, text, start + 1, held, expected, word, memory);
    }
    else
    {
      const std::vector<double> head = words(decodeBase64(text, start + 1, word), word);
      const double bytes = head.empty() ? 0 : head[0];
      if (!(bytes <= held) || (expected >= 0 && bytes != expected))
      {
        problem = headerClaim(
          name, "data", bytes, "where the array holds", expected >= 0 ? expected : held);
      }
    }
    if (!problem.empty())
    {
      return problem;
    }
  }
  return std::string();
}

/// The first megabyte of the input.
std::string headOf(const std::string& name, const std::string* text)
{
  return text ? text->substr(0, 1 << 20) : igaFileHead(name, 1 << 20);
}

/// Updates the reader with VTK's messages collected rather than printed (several lines each,
/// from the reader and its arrays and compressors); returns the first one's text, or sets
/// `error` for what the reader throws.
std::string updateQuietly(
  vtkXMLUnstructuredGridReader* reader, const std::string& name, std::string& error)
{
  const vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkNew<vtkStringOutputWindow> collected;
  vtkOutputWindow::SetInstance(collected);
  const vtkLogger::Verbosity verbosity = vtkLogger::GetCurrentVerbosityCutoff();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // VTK's log repeats each message
  try
  {
    reader->Update();
  }
  catch (const std::bad_alloc&)
  {
    error = "'" + name + "': not enough memory to read it (the sizes it gives are too large)";
  }
  catch (const std::exception& e)
  {
    error = "'" + name + "': cannot be read: " + e.what();
  }
  vtkLogger::SetStderrVerbosity(verbosity);
  vtkOutputWindow::SetInstance(previous);
  // VTK writes "ERROR: In FILE, line N\nCLASS (ADDRESS): TEXT\n\n".
  const std::string text = collected->GetOutput();
  const size_t open = text.find("(0x");
  const size_t start = open == std::string::npos ? open : text.find("): ", open);
  if (start == std::string::npos)
  {
    return std::string();
  }
  return text.substr(start + 3, text.find('\n', start) - (start + 3));
}
}

vtkSmartPointer<vtkUnstructuredGrid> vtkIGABezierFileReading::Read(const std::string& name,
  const std::string* text, iga::VolumeSet<double>& set, std::string& error,
  std::vector<std::string>& warnings, double memoryLimitBytes)
{
  set = iga::VolumeSet<double>();
  if (!text && !std::ifstream(name))
  {
    error = "cannot open '" + name + "'";
    return nullptr;
  }
  const double memory = memoryLimitBytes > 0
                          ? memoryLimitBytes
                          : double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  const std::string head = headOf(name, text);
  error = claimedSizesProblem(name, head, memory);
  if (error.empty())
  {
    error = binaryHeaderProblem(name, text ? *text : head, memory);
  }
  if (!error.empty())
  {
    return nullptr;
  }
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  if (text)
  {
    reader->ReadFromInputStringOn();
    reader->SetInputString(*text);
  }
  else
  {
    reader->SetFileName(name.c_str());
  }
  const std::string readerMessage = updateQuietly(reader, name, error);
  if (!error.empty())
  {
    return nullptr;
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->ShallowCopy(reader->GetOutput());
  if (reader->GetErrorCode() != 0 || grid->GetNumberOfCells() == 0)
  {
    error = "'" + name + "' is not a readable VTK XML unstructured grid with cells" +
            (readerMessage.empty() ? "" : " (" + readerMessage + ")");
    return nullptr;
  }
  if (!readerMessage.empty())
  {
    warnings.push_back(readerMessage);
  }
  if (!vtkIGABezierHexahedra::FromUnstructuredGrid(grid, set, error, warnings))
  {
    error = "'" + name + "': " + error;
    return nullptr;
  }
  if (set.attributeNames.empty())
  {
    error = "'" + name + "': no scalar point attribute to take an isosurface of";
    return nullptr;
  }
  return grid;
}
