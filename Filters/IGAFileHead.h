// What the readers check of a file before they open it, and its first bytes, shared by the
// readers that look at a file's start before reading it (its format, the sizes its header claims).
#pragma once

#include <sys/stat.h>

#include <fstream>
#include <string>

/// Empty when `name` is a regular file (links followed) or does not exist (the reader's own
/// message says so); otherwise why it is not read: opening a FIFO blocks until someone writes to
/// it, and a device or a FIFO may never end.
inline std::string igaNotRegularFileProblem(const std::string& name)
{
  struct stat status;
  if (stat(name.c_str(), &status) != 0 || S_ISREG(status.st_mode))
  {
    return std::string();
  }
  const char* kind = S_ISDIR(status.st_mode)    ? "a directory"
                     : S_ISFIFO(status.st_mode) ? "a FIFO"
                     : S_ISSOCK(status.st_mode) ? "a socket"
                                                : "a device";
  return "'" + name + "' is " + kind + ", not a regular file";
}

/// Opens `name` (binary) into `in` where it is a regular file; otherwise, or where it cannot be
/// opened, says why (igaNotRegularFileProblem, or "cannot open 'name'").
inline std::string igaOpenRegularFile(const std::string& name, std::ifstream& in)
{
  const std::string problem = igaNotRegularFileProblem(name);
  if (!problem.empty())
  {
    return problem;
  }
  in.open(name, std::ios::binary);
  return in ? std::string() : "cannot open '" + name + "'";
}

/// The first `bytes` bytes of a regular file; empty when it cannot be opened or is not a
/// regular file.
inline std::string igaFileHead(const std::string& name, size_t bytes)
{
  std::ifstream in;
  if (!igaOpenRegularFile(name, in).empty())
  {
    return std::string();
  }
  std::string head(bytes, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}
