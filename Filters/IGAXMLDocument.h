// XML text parsed into VTK's element tree safely: no element is built deeper than
// kIGAXMLMaxDepth (the tree is built and destroyed recursively, so a text nested tens of
// thousands of levels deep would overflow the stack), and the parser's error becomes one line.
// The G+Smo reader and the .pvd series reader parse through it.
#pragma once

#include "vtkSmartPointer.h"
#include "vtkXMLDataParser.h"

#include <string>

constexpr int kIGAXMLMaxDepth = 256;

/// The parser holding `text`'s element tree (GetRootElement), or null with `error` set:
/// "LINE: not well-formed XML (column C): what", or that the elements nest too deep. An XML
/// declaration after leading comments, which G+Smo accepts, is accepted too.
vtkSmartPointer<vtkXMLDataParser> igaParseXML(const std::string& text, std::string& error);
