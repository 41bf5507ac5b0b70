#include "IGAXMLDocument.h"

#include "vtkCallbackCommand.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cctype>
#include <regex>
#include <sstream>

namespace
{

/// vtkXMLDataParser that builds no element deeper than kIGAXMLMaxDepth.
class DepthLimitedParser : public vtkXMLDataParser
{
public:
  static DepthLimitedParser* New();
  vtkTypeMacro(DepthLimitedParser, vtkXMLDataParser);
  bool TooDeep = false;

protected:
  void StartElement(const char* name, const char** attributes) override
  {
    this->TooDeep = this->TooDeep || ++this->Depth > kIGAXMLMaxDepth;
    if (!this->TooDeep)
    {
      this->Superclass::StartElement(name, attributes);
    }
  }
  void EndElement(const char* name) override
  {
    if (!this->TooDeep)
    {
      this->Superclass::EndElement(name);
    }
    --this->Depth;
  }
  int ParsingComplete() override { return this->TooDeep || this->Superclass::ParsingComplete(); }

private:
  int Depth = 0;
};
vtkStandardNewMacro(DepthLimitedParser);

void storeMessage(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* message = static_cast<std::string*>(clientData);
  if (message->empty() && callData)
  {
    *message = static_cast<const char*>(callData);
  }
}

/// Where an XML declaration follows only whitespace and comments (G+Smo writes and reads such
/// files, e.g. its filedata/volumes/fichera.xml, though XML wants the declaration first), the
/// text with the declaration blanked out, lines and columns unchanged; else empty.
std::string withoutLateDeclaration(const std::string& text)
{
  size_t at = 0;
  for (;;)
  {
    at = text.find_first_not_of(" \t\r\n", at);
    if (at == std::string::npos || text.compare(at, 4, "<!--") != 0)
    {
      break;
    }
    const size_t end = text.find("-->", at + 4);
    if (end == std::string::npos)
    {
      return std::string(); // the parser says what is wrong
    }
    at = end + 3;
  }
  const size_t end = at == std::string::npos ? at : text.find("?>", at);
  if (at == 0 || end == std::string::npos || text.compare(at, 5, "<?xml") != 0 ||
      !std::isspace(static_cast<unsigned char>(text[at + 5])))
  {
    return std::string();
  }
  // Only a plain declaration of UTF-8 text may go: blanking one that holds markup or names
  // another encoding would hide what the parser has to say about it.
  std::string declaration = text.substr(at + 5, end - at - 5);
  std::transform(declaration.begin(), declaration.end(), declaration.begin(),
    [](unsigned char c) { return char(std::tolower(c)); });
  const size_t encoding = declaration.find("encoding");
  if (declaration.find_first_of("<>") != std::string::npos ||
      (encoding != std::string::npos && declaration.find("utf-8", encoding) == std::string::npos))
  {
    return std::string();
  }
  std::string fixed = text;
  for (size_t k = at; k < end + 2; ++k)
  {
    fixed[k] = fixed[k] == '\n' ? '\n' : ' ';
  }
  return fixed;
}

} // namespace

vtkSmartPointer<vtkXMLDataParser> igaParseXML(const std::string& text, std::string& error)
{
  const std::string fixed = withoutLateDeclaration(text);
  std::istringstream stream(fixed.empty() ? text : fixed);
  vtkNew<DepthLimitedParser> parser;
  parser->SetStream(&stream);
  parser->SetIgnoreCharacterData(0);
  std::string parserMessage;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(storeMessage);
  onError->SetClientData(&parserMessage);
  const unsigned long observer = parser->AddObserver(vtkCommand::ErrorEvent, onError);
  const bool parsed = parser->Parse() != 0;
  parser->RemoveObserver(observer); // it writes to parserMessage, gone on return
  parser->SetStream(nullptr);
  if (parser->TooDeep)
  {
    error = "elements are nested more than " + std::to_string(kIGAXMLMaxDepth) + " levels deep";
    return nullptr;
  }
  if (!parsed || !parser->GetRootElement())
  {
    // vtkXMLParser says "... at line L, column C, byte index B: what".
    std::smatch match;
    if (std::regex_search(parserMessage, match, std::regex("line ([0-9]+), column ([0-9]+)")))
    {
      const size_t colon = parserMessage.find(": ", match.position(0));
      error = match[1].str() + ": not well-formed XML (column " + match[2].str() + "): " +
              (colon == std::string::npos ? parserMessage : parserMessage.substr(colon + 2));
    }
    else
    {
      error = "not well-formed XML: " + parserMessage;
    }
    return nullptr;
  }
  return vtkSmartPointer<vtkXMLDataParser>(parser.Get());
}
