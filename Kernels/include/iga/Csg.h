// Constructive solid geometry over the solids of attributes, domains and half-spaces: the
// expression a user writes and the Boolean it stands for. VTK-free and engine-free; the engine's
// per-pixel classification (iga/sst/Csg.h) evaluates it along each ray.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace iga
{
namespace csg
{

/// A solid the expression combines. Every solid lies within the volumes it is drawn on: an
/// attribute's solid within the volumes holding the attribute, a half-space within all volumes.
struct Operand
{
  enum class Kind
  {
    Below,  ///< {x : attribute(x) < value}
    Above,  ///< {x : attribute(x) > value}
    Domain, ///< the volumes themselves
    Plane,  ///< the half-space plane[0] x + plane[1] y + plane[2] z + plane[3] >= 0
  };
  Kind kind = Kind::Domain;
  std::string attribute;
  double value = 0;
  std::array<double, 4> plane = { 0, 0, 0, 0 };
  size_t position = 0; ///< where the operand starts in the expression text
};

/// An expression tree stored flat, every node after its children: node `root` (the last) is the
/// whole, operands are leaves.
struct Expression
{
  enum class Op
  {
    Leaf,
    Union,
    Intersection,
    Difference,
  };
  struct Node
  {
    Op op = Op::Leaf;
    int left = -1, right = -1; ///< child nodes (operators)
    int operand = -1;          ///< index into operands (leaves)
  };
  std::vector<Operand> operands;
  std::vector<Node> nodes;
  int root = -1;

  /// Whether a point is in the result, given whether it is in each operand's solid (one entry
  /// per operand); `scratch` is resized to the nodes.
  bool contains(const std::vector<uint8_t>& inOperand, std::vector<uint8_t>& scratch) const;
  /// The expression written back in the grammar parseExpression reads, fully parenthesised.
  std::string text() const;
};

/// A syntax error: what is wrong and the 0-based character position where it is.
class ExpressionError : public std::invalid_argument
{
public:
  ExpressionError(const std::string& problem, size_t position);
  size_t position() const { return this->Position; }

private:
  size_t Position;
};

/// Whether a x + b y + c z + d = 0 is a plane: finite coefficients, a non-zero normal.
bool isPlane(const std::array<double, 4>& plane);

/// Checks an expression built by hand (parseExpression's are sound): its nodes, operands and
/// values. Throws std::invalid_argument naming the problem.
void checkExpression(const Expression& expression);

/// Most operands and deepest nesting an expression may have: a per-pixel classification keeps
/// one state per operand, and parsing recurses per level.
constexpr int kMaxOperands = 64;
constexpr int kMaxNesting = 64;

/// Reads an expression. Grammar:
///   expression := term (('|' | '-') term)*      union and difference, left to right
///   term       := factor ('&' factor)*           intersection binds tighter
///   factor     := '(' expression ')' | 'domain' | 'plane' '(' a ',' b ',' c ',' d ')'
///               | NAME '<' NUMBER | NAME '>' NUMBER
/// A NAME is letters, digits and _ . : (starting with a letter or _), or any text in double
/// quotes (a quoted "domain" or "plane" is an attribute's name). Throws ExpressionError naming
/// the problem and its position.
Expression parseExpression(const std::string& text);

/// The text of `expression` (blank: the volumes, `domain`) intersected with the half-spaces
/// a x + b y + c z + d >= 0 of `planes`: the solid of a capped clip. Unparsed: a bad expression
/// stays bad, its error positions shifted by the parenthesis put around it.
std::string cutByHalfSpaces(
  const std::string& expression, const std::vector<std::array<double, 4>>& planes);

} // namespace csg
} // namespace iga
