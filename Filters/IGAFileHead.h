// The first bytes of a file, shared by the readers that look at a file's start before reading
// it (its format, the sizes its header claims): empty when the file cannot be opened.
#pragma once

#include <fstream>
#include <string>

inline std::string igaFileHead(const std::string& name, size_t bytes)
{
  std::ifstream in(name, std::ios::binary);
  std::string head(bytes, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}
