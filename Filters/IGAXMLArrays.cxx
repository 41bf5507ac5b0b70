#include "IGAXMLArrays.h"

#include "vtkDataCompressor.h"
#include "vtkLZ4DataCompressor.h"
#include "vtkLZMADataCompressor.h"
#include "vtkSmartPointer.h"
#include "vtkZLibDataCompressor.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <vector>

namespace
{

/// The input, a string or a file, read at any position.
struct Input
{
  const std::string& name;
  const std::string* text;
  double size; ///< bytes

  std::string at(double position, size_t count) const
  {
    if (!(position >= 0 && position < size))
    {
      return std::string();
    }
    if (text)
    {
      return text->substr(size_t(position), count);
    }
    std::ifstream in(name, std::ios::binary);
    in.seekg(std::streamoff(position));
    std::string bytes(count, '\0');
    in.read(&bytes[0], std::streamsize(count));
    bytes.resize(size_t(in.gcount()));
    return bytes;
  }
};

/// What the VTKFile tag says about every binary array.
struct Encoding
{
  size_t word = 4; ///< header integers: UInt32 or UInt64
  bool bigEndian = false;
  std::string compressor; ///< VTK class name, empty when uncompressed
};

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

/// The tag that starts at `at` (up to its '>').
std::string tagAt(const std::string& text, size_t at)
{
  return text.substr(at, text.find('>', at) - at);
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

/// Unsigned integers of `size` bytes each from `bytes`, in the file's byte order.
std::vector<double> words(const std::string& bytes, size_t size, bool bigEndian)
{
  std::vector<double> result;
  for (size_t at = 0; at + size <= bytes.size(); at += size)
  {
    double value = 0;
    for (size_t k = 0; k < size; ++k)
    {
      const size_t b = bigEndian ? at + k : at + size - 1 - k;
      value = value * 256 + double(static_cast<unsigned char>(bytes[b]));
    }
    result.push_back(value);
  }
  return result;
}

/// A binary array's stream of bytes: its header, then its data (a compressed array's header is
/// base64-encoded apart from its data, an uncompressed one's with it).
struct Stream
{
  const Input* input;
  double start; ///< of the stream in the input
  bool base64;
  double held;                 ///< bytes it can decode to at most, -1 when its data cannot be found
  const char* fault = nullptr; ///< why an appended array's data cannot be found

  /// `count` bytes from byte `offset` of the part of the stream that starts at `part`.
  std::string bytes(double part, double offset, size_t count) const
  {
    if (!base64)
    {
      return input->at(part + offset, count);
    }
    // VTK writes base64 without whitespace past its start: 4 characters hold 3 bytes.
    const double quantum = std::floor(offset / 3);
    const size_t skip = size_t(offset - 3 * quantum);
    const std::string decoded =
      decodeBase64(input->at(part + 4 * quantum, 4 * ((count + skip) / 3 + 2)), 0, count + skip);
    return decoded.substr(std::min(skip, decoded.size()));
  }
};

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

/// A compressed array's header: its blocks, their uncompressed size and where its data starts.
struct Blocks
{
  double count = 0, size = 0, lastSize = 0; ///< lastSize: of a partial last block, or 0
  std::vector<double> compressed;           ///< bytes of each block
  double dataStart = 0;                     ///< of the compressed data in the input

  double total() const
  {
    return count == 0 ? 0 : (count - 1) * size + (lastSize > 0 ? lastSize : size);
  }
};

/// "" or why a compressed array's header disagrees with its data (`held` bytes at most), the
/// array (`expected` bytes, or -1 when unknown) or `memory`; fills `blocks`.
std::string compressedHeaderProblem(const std::string& name, const Stream& stream,
  const Encoding& encoding, double expected, double memory, Blocks& blocks)
{
  const size_t word = encoding.word;
  const std::vector<double> head =
    words(stream.bytes(stream.start, 0, 3 * word), word, encoding.bigEndian);
  if (head.empty())
  {
    return std::string(); // no header: VTK's reader says so
  }
  blocks.count = head[0];
  blocks.size = head.size() > 1 ? head[1] : 0;
  blocks.lastSize = head.size() > 2 ? head[2] : 0;
  if (!(blocks.size >= 1) || (blocks.count == 0 && blocks.lastSize != 0) ||
      !(blocks.lastSize <= blocks.size))
  {
    // VTK divides by the block size (a floating-point exception).
    return "'" + name + "': a binary data array's header gives inconsistent block sizes";
  }
  const double headerBytes = (3 + blocks.count) * double(word);
  if (!(headerBytes <= stream.held))
  {
    return headerClaim(name, "a table of blocks", headerBytes, "more than the data's", stream.held);
  }
  if (!(blocks.total() < memory))
  {
    return headerClaim(
      name, "uncompressed blocks", blocks.total(), "more than the memory's", memory);
  }
  if (expected >= 0 && blocks.total() != expected)
  {
    return headerClaim(
      name, "uncompressed blocks", blocks.total(), "where the array holds", expected);
  }
  const std::vector<double> table =
    words(stream.bytes(stream.start, 0, size_t(headerBytes)), word, encoding.bigEndian);
  blocks.compressed.assign(table.begin() + std::min<size_t>(3, table.size()), table.end());
  double compressedBytes = 0;
  for (double bytes : blocks.compressed)
  {
    compressedBytes += bytes;
  }
  blocks.dataStart = stream.start + (stream.base64 ? 4 * std::ceil(headerBytes / 3) : headerBytes);
  return compressedBytes <= stream.held - headerBytes
           ? std::string()
           : headerClaim(
               name, "compressed blocks", compressedBytes, "more than the data's", stream.held);
}

/// Bytes of an array element of the tag's type, or 0 for a type VTK's arrays do not have.
double elementBytes(const std::string& tag)
{
  const std::string type = attributeOf(tag, "type=\"");
  return type == "Int8" || type == "UInt8"                          ? 1
         : type == "Int16" || type == "UInt16"                      ? 2
         : type == "Int32" || type == "UInt32" || type == "Float32" ? 4
         : type == "Int64" || type == "UInt64" || type == "Float64" ? 8
                                                                    : 0;
}

/// The tuples of the data array whose tag starts at `at`: its NumberOfTuples (field data), else
/// its piece's points (points, point data) or cells (cell data, cell types and offsets), or -1
/// (connectivity).
double claimedTuples(const std::string& text, size_t at)
{
  const std::string tag = tagAt(text, at);
  const std::string given = attributeOf(tag, "NumberOfTuples=\"");
  if (!given.empty())
  {
    return std::strtod(given.c_str(), nullptr);
  }
  const size_t piece = text.rfind("<Piece", at);
  if (piece == std::string::npos)
  {
    return -1;
  }
  size_t section = std::string::npos;
  std::string sectionTag;
  for (const char* name : { "<Points", "<PointData", "<Cells", "<CellData", "<FieldData" })
  {
    const size_t found = text.rfind(name, at);
    if (found != std::string::npos && found > piece &&
        (section == std::string::npos || found > section))
    {
      section = found;
      sectionTag = name;
    }
  }
  const std::string pieceTag = tagAt(text, piece), arrayName = attributeOf(tag, "Name=\"");
  if (sectionTag == "<Points" || sectionTag == "<PointData")
  {
    return std::strtod(attributeOf(pieceTag, "NumberOfPoints=\"").c_str(), nullptr);
  }
  if (sectionTag == "<CellData" ||
      (sectionTag == "<Cells" && (arrayName == "types" || arrayName == "offsets")))
  {
    return std::strtod(attributeOf(pieceTag, "NumberOfCells=\"").c_str(), nullptr);
  }
  return -1;
}

/// Components a tuple of the tag's array (1 when it does not say).
double componentsOf(const std::string& tag)
{
  const std::string components = attributeOf(tag, "NumberOfComponents=\"");
  return components.empty() ? 1 : std::strtod(components.c_str(), nullptr);
}

/// The bytes the data array whose tag starts at `at` must decode to when the file says how many
/// tuples it has, else -1.
double expectedBytes(const std::string& text, size_t at)
{
  const std::string tag = tagAt(text, at);
  const double tuples = claimedTuples(text, at), size = elementBytes(tag);
  return tuples >= 0 && size > 0 ? tuples * componentsOf(tag) * size : -1;
}

/// The attribute's text as a whole number of at least `lowest`, or NaN when it is not one.
double wholeNumber(const std::string& text, double lowest)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  return !text.empty() && *end == '\0' && value >= lowest && value == std::floor(value)
           ? value
           : std::nan("");
}

/// "" or why the tag at `at` gives its array a size VTK cannot allocate within `memory`: a
/// component count that is no positive whole number, or tuples of more bytes than the memory.
std::string claimedArrayProblem(
  const std::string& name, const std::string& head, size_t at, double memory)
{
  const std::string tag = tagAt(head, at), arrayName = attributeOf(tag, "Name=\"");
  const std::string components = attributeOf(tag, "NumberOfComponents=\"");
  const double count = components.empty() ? 1 : wholeNumber(components, 1);
  char text[320];
  if (std::isnan(count))
  {
    std::snprintf(text, sizeof text,
      "'%s': data array '%.64s' has NumberOfComponents=\"%.32s\", not a positive whole number",
      name.c_str(), arrayName.c_str(), components.c_str());
    return text;
  }
  const std::string tuplesText = attributeOf(tag, "NumberOfTuples=\"");
  if (!tuplesText.empty() && std::isnan(wholeNumber(tuplesText, 0)))
  {
    std::snprintf(text, sizeof text,
      "'%s': data array '%.64s' has NumberOfTuples=\"%.32s\", not a whole number", name.c_str(),
      arrayName.c_str(), tuplesText.c_str());
    return text;
  }
  // Strings and unknown types at 8 bytes a value at least.
  const double bytes =
    claimedTuples(head, at) * count * (elementBytes(tag) > 0 ? elementBytes(tag) : 8);
  if (!(bytes < memory))
  {
    std::snprintf(text, sizeof text,
      "'%s': data array '%.64s' claims %.4g bytes (%.4g components a tuple), more than this "
      "machine's %.3g GB",
      name.c_str(), arrayName.c_str(), bytes, count, memory / 1e9);
    return text;
  }
  return std::string();
}

/// A binary data array of the input as its tag places it.
struct BinaryArray
{
  Stream stream;
  double expected = -1;  ///< bytes, or -1 when its piece does not say
  double dataBytes = -1; ///< uncompressed bytes its header gives
  Blocks blocks;         ///< when compressed
  double dataStart = 0;  ///< of an uncompressed array's data in its stream's bytes
};

/// Where the next '<' after `from` lies in the input (its size when there is none): in `head`,
/// else past it in the file.
double nextTag(const Input& input, const std::string& head, size_t from)
{
  const size_t inHead = head.find('<', from);
  if (inHead != std::string::npos)
  {
    return double(inHead);
  }
  for (double at = double(head.size()); at < input.size; at += 1 << 20)
  {
    const size_t found = input.at(at, 1 << 20).find('<');
    if (found != std::string::npos)
    {
      return at + double(found);
    }
  }
  return input.size;
}

/// The stream of the binary array whose tag starts at `at` in `head`, or held < 0 when its
/// data cannot be found (VTK's reader says so).
Stream streamOf(const Input& input, const std::string& head, size_t at)
{
  const std::string tag = tagAt(head, at);
  Stream stream{ &input, 0, true, -1 };
  if (attributeOf(tag, "format=\"") == "binary")
  {
    const size_t open = head.find('>', at);
    const size_t first =
      open == std::string::npos ? open : head.find_first_not_of(" \t\r\n", open + 1);
    if (first == std::string::npos)
    {
      return stream;
    }
    stream.start = double(first);
    stream.held = 0.75 * (nextTag(input, head, first) - stream.start);
    return stream;
  }
  // As VTK's reader: the data start at the first character after the AppendedData tag that is
  // no white space, past it when it is the '_' VTK writes.
  const size_t appended = head.find("<AppendedData");
  const size_t close = appended == std::string::npos ? appended : head.find('>', appended);
  const size_t first =
    close == std::string::npos ? close : head.find_first_not_of(" \t\r\n", close + 1);
  const double offset = wholeNumber(attributeOf(tag, "offset=\""), 0);
  if (first == std::string::npos)
  {
    stream.fault = "has no appended data";
    return stream;
  }
  if (std::isnan(offset))
  {
    stream.fault = "has no offset into the appended data that is a whole number";
    return stream;
  }
  stream.base64 = attributeOf(tagAt(head, appended), "encoding=\"") == "base64";
  stream.start = double(first + (head[first] == '_' ? 1 : 0)) + offset;
  const double left = input.size - stream.start;
  stream.held = left < 0 ? -1 : stream.base64 ? 0.75 * left : left;
  return stream;
}

/// "" or why the binary array whose tag starts at `at` has a header that disagrees with its
/// data or its size: VTK allocates what the header says (a compressed array's table of blocks,
/// each compressed block, an uncompressed array's byte count) and copies the blocks into the
/// array as sized by the piece, so a header claiming more than the data holds, more than
/// `memory` or another size than the array's overflows, crashes or allocates gigabytes.
std::string headerProblem(const Input& input, const std::string& head, size_t at,
  const Encoding& encoding, double memory, BinaryArray& array)
{
  array.stream = streamOf(input, head, at);
  array.expected = expectedBytes(head, at);
  if (array.stream.fault)
  {
    return "'" + input.name + "': data array '" + attributeOf(tagAt(head, at), "Name=\"") +
           "' is appended, but the file " + array.stream.fault;
  }
  if (array.stream.held < 0)
  {
    return std::string();
  }
  if (!encoding.compressor.empty())
  {
    const std::string problem = compressedHeaderProblem(
      input.name, array.stream, encoding, array.expected, memory, array.blocks);
    array.dataBytes = array.blocks.size > 0 ? array.blocks.total() : -1; // -1: no header
    return problem;
  }
  const std::vector<double> header = words(
    array.stream.bytes(array.stream.start, 0, encoding.word), encoding.word, encoding.bigEndian);
  if (header.empty())
  {
    array.dataBytes = -1;
    return std::string(); // no header: VTK's reader says so
  }
  array.dataBytes = header[0];
  array.dataStart = double(encoding.word);
  const double held = array.stream.held - double(encoding.word);
  if (!(array.dataBytes <= held))
  {
    return headerClaim(input.name, "data", array.dataBytes, "more than the data's", held);
  }
  if (array.expected >= 0 && array.dataBytes != array.expected)
  {
    return headerClaim(
      input.name, "data", array.dataBytes, "where the array holds", array.expected);
  }
  return std::string();
}

/// Block `block` of a compressed array whose header passed, uncompressed ("" when it cannot be).
std::string blockBytes(const BinaryArray& array, const Encoding& encoding, size_t block)
{
  const Blocks& blocks = array.blocks;
  if (block >= blocks.compressed.size())
  {
    return std::string();
  }
  double before = 0;
  for (size_t b = 0; b < block; ++b)
  {
    before += blocks.compressed[b];
  }
  vtkSmartPointer<vtkDataCompressor> compressor;
  if (encoding.compressor == "vtkZLibDataCompressor")
    compressor = vtkSmartPointer<vtkZLibDataCompressor>::New();
  else if (encoding.compressor == "vtkLZ4DataCompressor")
    compressor = vtkSmartPointer<vtkLZ4DataCompressor>::New();
  else if (encoding.compressor == "vtkLZMADataCompressor")
    compressor = vtkSmartPointer<vtkLZMADataCompressor>::New();
  if (!compressor)
  {
    return std::string();
  }
  try
  {
    const std::string compressed =
      array.stream.bytes(blocks.dataStart, before, size_t(blocks.compressed[block]));
    const bool last = double(block) + 1 == blocks.count;
    std::string plain(size_t(last && blocks.lastSize > 0 ? blocks.lastSize : blocks.size), '\0');
    return compressor->Uncompress(reinterpret_cast<const unsigned char*>(compressed.data()),
             compressed.size(), reinterpret_cast<unsigned char*>(&plain[0]),
             plain.size()) == plain.size()
             ? plain
             : std::string();
  }
  catch (const std::bad_alloc&)
  {
    return std::string(); // a block beyond what can be held: VTK's reader fails on it too
  }
}

/// The uncompressed bytes [offset, offset + count) of a binary array whose header passed, across
/// blocks where they span two ("" when they cannot be read).
std::string arrayBytes(
  const BinaryArray& array, const Encoding& encoding, double offset, size_t count)
{
  if (encoding.compressor.empty())
  {
    return array.stream.bytes(array.stream.start, array.dataStart + offset, count);
  }
  std::string bytes;
  while (bytes.size() < count)
  {
    // No header read (block size 0) or past the blocks: nothing to read.
    const double block = std::floor(offset / array.blocks.size);
    if (!(block >= 0 && block < double(array.blocks.compressed.size())))
    {
      return std::string();
    }
    const std::string plain = blockBytes(array, encoding, size_t(block));
    const size_t within = size_t(offset - block * array.blocks.size);
    if (within >= plain.size())
    {
      return std::string();
    }
    const std::string piece = plain.substr(within, count - bytes.size());
    bytes += piece;
    offset += double(piece.size());
  }
  return bytes;
}

/// An integer of `size` bytes in the file's byte order, signed for the tag's Int types.
double integerValue(const std::string& bytes, size_t size, bool bigEndian, bool isSigned)
{
  const std::vector<double> value = words(bytes, size, bigEndian);
  if (value.empty())
  {
    return std::nan("");
  }
  const double range = std::ldexp(1.0, int(8 * size));
  return isSigned && value[0] >= range / 2 ? value[0] - range : value[0];
}

/// The last number of an ASCII array's text.
double lastAsciiValue(const Input& input, const std::string& head, size_t at)
{
  const size_t open = head.find('>', at);
  if (open == std::string::npos)
  {
    return std::nan("");
  }
  const double close = nextTag(input, head, open + 1);
  const std::string text = input.at(double(open + 1), size_t(close - double(open + 1)));
  const size_t end = text.find_last_not_of(" \t\r\n");
  if (end == std::string::npos)
  {
    return std::nan("");
  }
  const size_t begin = text.find_last_of(" \t\r\n", end);
  return std::strtod(text.c_str() + (begin == std::string::npos ? 0 : begin + 1), nullptr);
}

/// "" or why a piece's cell offsets (whose tag starts at `at`) would have VTK allocate a
/// connectivity beyond `memory` or beyond the connectivity array's data (`connectivity` ids,
/// or -1 when unknown): VTK reads the last offset as the connectivity's size.
std::string offsetsProblem(const Input& input, const std::string& head, size_t at,
  const Encoding& encoding, const BinaryArray* array, double connectivity, double memory)
{
  const std::string tag = tagAt(head, at);
  const double size = elementBytes(tag);
  const std::string pieceTag = tagAt(head, head.rfind("<Piece", at));
  const double cells = std::strtod(attributeOf(pieceTag, "NumberOfCells=\"").c_str(), nullptr);
  if (!(cells >= 1) || size == 0)
  {
    return std::string();
  }
  const double last =
    array ? integerValue(arrayBytes(*array, encoding, (cells - 1) * size, size_t(size)),
              size_t(size), encoding.bigEndian, attributeOf(tag, "type=\"")[0] == 'I')
          : lastAsciiValue(input, head, at);
  char text[320];
  if (std::isnan(last) && array)
  {
    return std::string(); // unreadable: VTK's reader says so
  }
  if (std::isnan(last)) // VTK would read no ASCII values and take its unset last one
  {
    std::snprintf(text, sizeof text,
      "'%s': its cell offsets (format '%s', read as ASCII) hold no readable last value",
      input.name.c_str(), attributeOf(tag, "format=\"").c_str());
    return text;
  }
  if (!(last >= 0 && last * 8 < memory))
  {
    std::snprintf(text, sizeof text,
      "'%s': its cell offsets end at %.4g, a connectivity of %.3g GB, more than this machine's "
      "%.3g GB",
      input.name.c_str(), last, last * 8 / 1e9, memory / 1e9);
    return text;
  }
  if (connectivity >= 0 && last > connectivity)
  {
    std::snprintf(text, sizeof text,
      "'%s': its cell offsets end at %.0f, past the %.0f point ids of its connectivity",
      input.name.c_str(), last, connectivity);
    return text;
  }
  return std::string();
}

} // namespace

std::string igaXMLArrayProblem(
  const std::string& name, const std::string* text, const std::string& head, double memory)
{
  std::ifstream file;
  double size = text ? double(text->size()) : 0;
  if (!text)
  {
    file.open(name, std::ios::binary | std::ios::ate);
    size = file ? double(file.tellg()) : 0;
  }
  const Input input{ name, text, size };
  const std::string fileTag = tagAt(head, std::min(head.find("<VTKFile"), head.size()));
  Encoding encoding;
  encoding.word = attributeOf(fileTag, "header_type=\"") == "UInt64" ? 8 : 4;
  encoding.bigEndian = attributeOf(fileTag, "byte_order=\"") == "BigEndian";
  encoding.compressor = attributeOf(fileTag, "compressor=\"");
  double connectivity = -1; // ids of the piece's connectivity, when its header says
  for (size_t at = head.find("<DataArray"); at != std::string::npos;
       at = head.find("<DataArray", at + 1))
  {
    const std::string tag = tagAt(head, at), format = attributeOf(tag, "format=\"");
    const std::string arrayName = attributeOf(tag, "Name=\"");
    BinaryArray array;
    const bool binary = format == "binary" || format == "appended";
    std::string problem = claimedArrayProblem(name, head, at, memory);
    if (problem.empty() && binary)
    {
      problem = headerProblem(input, head, at, encoding, memory, array);
    }
    if (problem.empty() && arrayName == "connectivity")
    {
      connectivity = binary && elementBytes(tag) > 0 ? array.dataBytes / elementBytes(tag) : -1;
    }
    // Offsets in any format but binary and appended VTK reads as ASCII text (a mistyped format
    // attribute too).
    const size_t cells = head.rfind("<Cells", at), piece = head.rfind("<Piece", at);
    if (problem.empty() && arrayName == "offsets" && cells != std::string::npos &&
        piece != std::string::npos && cells > piece)
    {
      problem =
        offsetsProblem(input, head, at, encoding, binary ? &array : nullptr, connectivity, memory);
    }
    if (!problem.empty())
    {
      return problem;
    }
  }
  return std::string();
}
