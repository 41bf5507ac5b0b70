#include "iga/Csg.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>

namespace iga
{
namespace csg
{

ExpressionError::ExpressionError(const std::string& problem, size_t position)
  : std::invalid_argument(problem + " at position " + std::to_string(position))
  , Position(position)
{
}

bool Expression::contains(
  const std::vector<uint8_t>& inOperand, std::vector<uint8_t>& scratch) const
{
  scratch.resize(this->nodes.size());
  for (size_t n = 0; n < this->nodes.size(); ++n)
  {
    const Node& node = this->nodes[n];
    const auto left = node.left >= 0 ? scratch[size_t(node.left)] : 0;
    const auto right = node.right >= 0 ? scratch[size_t(node.right)] : 0;
    switch (node.op)
    {
      case Op::Leaf:
        scratch[n] = inOperand[size_t(node.operand)];
        break;
      case Op::Union:
        scratch[n] = left || right;
        break;
      case Op::Intersection:
        scratch[n] = left && right;
        break;
      case Op::Difference:
        scratch[n] = left && !right;
        break;
    }
  }
  return scratch[size_t(this->root)] != 0;
}

namespace
{

std::string operandText(const Operand& operand)
{
  std::ostringstream out;
  out.precision(17);
  switch (operand.kind)
  {
    case Operand::Kind::Below:
    case Operand::Kind::Above:
      out << '"' << operand.attribute << '"' << (operand.kind == Operand::Kind::Below ? '<' : '>')
          << operand.value;
      break;
    case Operand::Kind::Domain:
      out << "domain";
      break;
    case Operand::Kind::Plane:
      out << "plane(" << operand.plane[0] << ',' << operand.plane[1] << ',' << operand.plane[2]
          << ',' << operand.plane[3] << ')';
      break;
  }
  return out.str();
}

/// Recursive descent over the grammar of parseExpression, one function per rule.
class Parser
{
public:
  explicit Parser(const std::string& text)
    : Text(text)
  {
  }

  Expression parse()
  {
    this->Result.root = this->expression(0);
    this->skipSpace();
    if (this->At < this->Text.size())
    {
      throw ExpressionError(
        std::string("unexpected '") + this->Text[this->At] + "' after a complete expression",
        this->At);
    }
    return std::move(this->Result);
  }

private:
  int expression(int depth)
  {
    int left = this->term(depth);
    for (char c = this->peek(); c == '|' || c == '-'; c = this->peek())
    {
      ++this->At;
      const int right = this->term(depth);
      left = this->join(c == '|' ? Expression::Op::Union : Expression::Op::Difference, left, right);
    }
    return left;
  }

  int term(int depth)
  {
    int left = this->factor(depth);
    while (this->peek() == '&')
    {
      ++this->At;
      left = this->join(Expression::Op::Intersection, left, this->factor(depth));
    }
    return left;
  }

  int factor(int depth)
  {
    const char c = this->peek();
    const size_t start = this->At;
    if (c == '(')
    {
      if (depth >= kMaxNesting)
      {
        throw ExpressionError(
          "parentheses nested deeper than " + std::to_string(kMaxNesting) + " levels", start);
      }
      ++this->At;
      const int inner = this->expression(depth + 1);
      const char next = this->peek();
      if (next == '\0')
      {
        throw ExpressionError("'(' is never closed", start);
      }
      if (next != ')')
      {
        throw ExpressionError(
          std::string("unexpected '") + next + "' where an operator or ')' is expected", this->At);
      }
      ++this->At;
      return inner;
    }
    if (c == '\0')
    {
      throw ExpressionError("expression ends where an operand or '(' is expected", start);
    }
    const bool quoted = this->Text[start] == '"';
    const std::string name = this->name();
    const char comparison = this->peek();
    Operand operand;
    operand.position = start;
    if (comparison == '<' || comparison == '>')
    {
      ++this->At;
      operand.kind = comparison == '<' ? Operand::Kind::Below : Operand::Kind::Above;
      operand.attribute = name;
      operand.value = this->number("a value after '" + std::string(1, comparison) + "'");
    }
    else if (name == "domain" && !quoted)
    {
      operand.kind = Operand::Kind::Domain;
    }
    else if (name == "plane" && !quoted)
    {
      operand.kind = Operand::Kind::Plane;
      this->plane(operand);
    }
    else
    {
      throw ExpressionError(
        "'" + name + "' needs '<' or '>' and a value (or is it domain or plane?)", start);
    }
    return this->leaf(operand);
  }

  void plane(Operand& operand)
  {
    this->expect('(', "'(' after plane");
    for (int k = 0; k < 4; ++k)
    {
      if (k > 0)
      {
        this->expect(',', "',' between the plane's four coefficients");
      }
      operand.plane[size_t(k)] = this->number("coefficient " + std::to_string(k + 1) + " of plane");
    }
    this->expect(')', "')' after the plane's four coefficients");
    if (!isPlane(operand.plane))
    {
      throw ExpressionError("plane has a zero normal (a, b, c)", operand.position);
    }
  }

  std::string name()
  {
    const size_t start = this->At;
    if (this->Text[start] == '"')
    {
      const size_t close = this->Text.find('"', start + 1);
      if (close == std::string::npos)
      {
        throw ExpressionError("quoted name is never closed", start);
      }
      this->At = close + 1;
      if (close == start + 1)
      {
        throw ExpressionError("empty attribute name", start);
      }
      return this->Text.substr(start + 1, close - start - 1);
    }
    auto nameChar = [](char c)
    { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == ':'; };
    const char first = this->Text[start];
    if (!(std::isalpha(static_cast<unsigned char>(first)) || first == '_'))
    {
      throw ExpressionError(
        std::string("unexpected '") + first + "' where an operand is expected", start);
    }
    while (this->At < this->Text.size() && nameChar(this->Text[this->At]))
    {
      ++this->At;
    }
    return this->Text.substr(start, this->At - start);
  }

  double number(const std::string& what)
  {
    this->skipSpace();
    // from_chars, not strtod: a decimal point whatever the locale.
    const char* begin = this->Text.c_str() + this->At;
    const char* last = this->Text.c_str() + this->Text.size();
    double value = 0;
    const bool plus = *begin == '+';
    const auto read = std::from_chars(begin + (plus ? 1 : 0), last, value);
    if (read.ec == std::errc::invalid_argument || (plus && (begin[1] == '-' || begin[1] == '+')))
    {
      throw ExpressionError("expected " + what, this->At);
    }
    if (read.ec == std::errc::result_out_of_range || !std::isfinite(value))
    {
      throw ExpressionError(what + " is beyond the range of double", this->At);
    }
    this->At += size_t(read.ptr - begin);
    return value;
  }

  int leaf(const Operand& operand)
  {
    if (int(this->Result.operands.size()) >= kMaxOperands)
    {
      throw ExpressionError(
        "more than " + std::to_string(kMaxOperands) + " operands", operand.position);
    }
    Expression::Node node;
    node.operand = int(this->Result.operands.size());
    this->Result.operands.push_back(operand);
    this->Result.nodes.push_back(node);
    return int(this->Result.nodes.size()) - 1;
  }

  int join(Expression::Op op, int left, int right)
  {
    Expression::Node node;
    node.op = op;
    node.left = left;
    node.right = right;
    this->Result.nodes.push_back(node);
    return int(this->Result.nodes.size()) - 1;
  }

  void expect(char c, const std::string& what)
  {
    if (this->peek() != c)
    {
      throw ExpressionError("expected " + what, this->At);
    }
    ++this->At;
  }

  /// The next character after spaces, '\0' at the end.
  char peek()
  {
    this->skipSpace();
    return this->At < this->Text.size() ? this->Text[this->At] : '\0';
  }

  void skipSpace()
  {
    while (this->At < this->Text.size() &&
           std::isspace(static_cast<unsigned char>(this->Text[this->At])))
    {
      ++this->At;
    }
  }

  const std::string& Text;
  size_t At = 0;
  Expression Result;
};

} // namespace

std::string Expression::text() const
{
  const std::function<std::string(int)> at = [&](int n) -> std::string
  {
    const Node& node = this->nodes[size_t(n)];
    const char* symbol = node.op == Op::Union ? " | " : node.op == Op::Intersection ? " & " : " - ";
    return node.op == Op::Leaf ? operandText(this->operands[size_t(node.operand)])
                               : "(" + at(node.left) + symbol + at(node.right) + ")";
  };
  return at(this->root);
}

bool isPlane(const std::array<double, 4>& plane)
{
  return std::isfinite(plane[0]) && std::isfinite(plane[1]) && std::isfinite(plane[2]) &&
         std::isfinite(plane[3]) && !(plane[0] == 0 && plane[1] == 0 && plane[2] == 0);
}

void checkExpression(const Expression& e)
{
  if (e.operands.size() > size_t(kMaxOperands))
  {
    throw std::invalid_argument(
      "the expression has more than " + std::to_string(kMaxOperands) + " operands");
  }
  for (size_t k = 0; k < e.operands.size(); ++k)
  {
    const Operand& o = e.operands[k];
    const bool attribute = o.kind == Operand::Kind::Below || o.kind == Operand::Kind::Above;
    if ((attribute && (o.attribute.empty() || !std::isfinite(o.value))) ||
        (o.kind == Operand::Kind::Plane && !isPlane(o.plane)))
    {
      throw std::invalid_argument("operand " + std::to_string(k) +
                                  " of the expression has no attribute, a value that is not "
                                  "finite, or a plane that is not one");
    }
  }
  for (size_t n = 0; n < e.nodes.size(); ++n)
  {
    const Expression::Node& node = e.nodes[n];
    const bool leaf = node.op == Expression::Op::Leaf;
    const bool sound =
      leaf ? node.operand >= 0 && size_t(node.operand) < e.operands.size()
           : node.left >= 0 && node.right >= 0 && size_t(node.left) < n && size_t(node.right) < n;
    if (!sound)
    {
      throw std::invalid_argument(
        "node " + std::to_string(n) + " of the expression refers to no operand or later node");
    }
  }
  if (e.root >= 0 && size_t(e.root) + 1 != e.nodes.size())
  {
    throw std::invalid_argument("the expression's root is not its last node");
  }
}

Expression parseExpression(const std::string& text)
{
  if (text.find('\0') != std::string::npos)
  {
    throw ExpressionError("expression holds a NUL character", text.find('\0'));
  }
  return Parser(text).parse();
}

std::string cutByHalfSpaces(
  const std::string& expression, const std::vector<std::array<double, 4>>& planes)
{
  if (planes.empty())
  {
    return expression;
  }
  const bool blank = expression.find_first_not_of(" \t\r\n") == std::string::npos;
  std::string text = blank ? "domain" : "(" + expression + ")";
  for (const auto& plane : planes)
  {
    char term[160];
    std::snprintf(term, sizeof term, " & plane(%.17g,%.17g,%.17g,%.17g)", plane[0], plane[1],
      plane[2], plane[3]);
    text += term;
  }
  return text;
}

} // namespace csg
} // namespace iga
