// Polynomials in x, y, z written as text: "(x^2 + 2.25*y^2 + z^2 - 1)^3 - x^2*z^3", the input of
// algebraic surfaces. Grammar: sums and differences of products; factors are decimal numbers,
// x, y, z, parenthesised expressions, a factor to a whole power (^ binds tighter than a sign,
// so -x^2 is -(x^2)), and division by a nonzero constant. Errors name their position (1-based).
#pragma once

#include "iga/Polynomial.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace iga
{

/// The highest total degree an algebraic surface may have (the ray's polynomial degree).
constexpr int kMaxAlgebraicDegree = kMaxDegree;
/// The deepest parentheses and signs an expression may nest: parsing recurses per level, so
/// deeper text is refused rather than overflowing the stack.
constexpr int kMaxExpressionNesting = 64;

namespace detail
{
/// Calls fn(a, b, c, coefficient) for the nonzero coefficients of p.
template<class Fn>
void forEachTerm(const Polynomial3<double>& p, Fn fn)
{
  for (int c = 0; c <= p.degree[2]; ++c)
  {
    for (int b = 0; b <= p.degree[1]; ++b)
    {
      for (int a = 0; a <= p.degree[0]; ++a)
      {
        if (p.at(a, b, c) != 0)
        {
          fn(a, b, c, p.at(a, b, c));
        }
      }
    }
  }
}

/// p * q in power form (degrees add per variable).
inline Polynomial3<double> multiply(const Polynomial3<double>& p, const Polynomial3<double>& q)
{
  Polynomial3<double> r(
    p.degree[0] + q.degree[0], p.degree[1] + q.degree[1], p.degree[2] + q.degree[2]);
  forEachTerm(p,
    [&](int a, int b, int c, double v) {
      forEachTerm(q, [&](int i, int j, int k, double w) { r.at(a + i, b + j, c + k) += v * w; });
    });
  return r;
}

/// p + sign q.
inline Polynomial3<double> add(
  const Polynomial3<double>& p, const Polynomial3<double>& q, double sign)
{
  Polynomial3<double> r(std::max(p.degree[0], q.degree[0]), std::max(p.degree[1], q.degree[1]),
    std::max(p.degree[2], q.degree[2]));
  forEachTerm(p, [&](int a, int b, int c, double v) { r.at(a, b, c) += v; });
  forEachTerm(q, [&](int a, int b, int c, double v) { r.at(a, b, c) += sign * v; });
  return r;
}

inline Polynomial3<double> constant(double v)
{
  Polynomial3<double> r(0, 0, 0);
  r.at(0, 0, 0) = v;
  return r;
}

/// The highest a + b + c with a nonzero coefficient (0 for the zero polynomial).
inline int totalDegree(const Polynomial3<double>& p)
{
  int degree = 0;
  forEachTerm(p, [&](int a, int b, int c, double) { degree = std::max(degree, a + b + c); });
  return degree;
}

class ExpressionParser
{
public:
  explicit ExpressionParser(const std::string& text)
    : Text(text)
  {
  }

  Polynomial3<double> parse()
  {
    Polynomial3<double> p = this->sum();
    this->skipSpace();
    if (this->Position < this->Text.size())
    {
      this->fail(this->Text[this->Position] == ')' ? "unbalanced ')'" : "expected an operator");
    }
    return p;
  }

private:
  const std::string& Text;
  size_t Position = 0;
  int Depth = 0;

  [[noreturn]] void fail(const std::string& what, size_t at) const
  {
    throw std::invalid_argument("expression, position " + std::to_string(at + 1) + ": " + what);
  }
  [[noreturn]] void fail(const std::string& what) const { this->fail(what, this->Position); }

  /// Whether the character at `at` is of a <cctype> class ('s'pace, 'd'igit, 'a'lpha, alnu'm').
  bool isAt(char kind, size_t at) const
  {
    if (at >= this->Text.size())
    {
      return false;
    }
    const int ch = static_cast<unsigned char>(this->Text[at]);
    return kind == 's'   ? std::isspace(ch) != 0
           : kind == 'd' ? std::isdigit(ch) != 0
           : kind == 'a' ? std::isalpha(ch) != 0
                         : std::isalnum(ch) != 0;
  }
  void skipSpace()
  {
    while (this->isAt('s', this->Position))
    {
      ++this->Position;
    }
  }
  bool accept(char c)
  {
    this->skipSpace();
    const bool found = this->Position < this->Text.size() && this->Text[this->Position] == c;
    this->Position += found ? 1 : 0;
    return found;
  }

  /// Refuses a result of too high a degree where it was formed, before it grows further.
  Polynomial3<double> checked(Polynomial3<double> p, size_t at) const
  {
    if (std::max(std::max(p.degree[0], p.degree[1]), p.degree[2]) > kMaxAlgebraicDegree)
    {
      this->fail("degree above " + std::to_string(kMaxAlgebraicDegree), at);
    }
    return p;
  }

  Polynomial3<double> sum()
  {
    Polynomial3<double> p = this->product();
    for (;;)
    {
      if (this->accept('+'))
      {
        p = add(p, this->product(), 1.0);
      }
      else if (this->accept('-'))
      {
        p = add(p, this->product(), -1.0);
      }
      else
      {
        return p;
      }
    }
  }

  Polynomial3<double> product()
  {
    Polynomial3<double> p = this->signedFactor();
    for (;;)
    {
      const size_t at = this->Position;
      if (this->accept('*'))
      {
        p = this->checked(multiply(p, this->signedFactor()), at);
      }
      else if (this->accept('/'))
      {
        this->skipSpace();
        const size_t divisorAt = this->Position;
        const Polynomial3<double> q = this->signedFactor();
        if (totalDegree(q) > 0 || q.at(0, 0, 0) == 0)
        {
          this->fail("division only by a nonzero constant", divisorAt);
        }
        p = multiply(p, constant(1.0 / q.at(0, 0, 0)));
      }
      else
      {
        return p;
      }
    }
  }

  /// parse() one level deeper, at `at` (an opening parenthesis or a sign).
  template<class Parse>
  Polynomial3<double> deeper(size_t at, Parse parse)
  {
    if (this->Depth >= kMaxExpressionNesting)
    {
      this->fail(
        "parentheses and signs nested deeper than " + std::to_string(kMaxExpressionNesting), at);
    }
    ++this->Depth;
    Polynomial3<double> p = parse();
    --this->Depth;
    return p;
  }

  Polynomial3<double> signedFactor()
  {
    this->skipSpace();
    const size_t at = this->Position;
    if (this->accept('-'))
    {
      return multiply(constant(-1.0), this->deeper(at, [this] { return this->signedFactor(); }));
    }
    if (this->accept('+'))
    {
      return this->deeper(at, [this] { return this->signedFactor(); });
    }
    return this->power();
  }

  Polynomial3<double> power()
  {
    const Polynomial3<double> base = this->primary();
    const size_t at = this->Position;
    if (!this->accept('^'))
    {
      return base;
    }
    this->skipSpace();
    const size_t exponentAt = this->Position;
    size_t end = exponentAt;
    while (this->isAt('d', end))
    {
      ++end;
    }
    if (end == exponentAt)
    {
      this->fail("expected a whole exponent after '^'");
    }
    const std::string digits = this->Text.substr(exponentAt, end - exponentAt);
    if (digits.size() > 3 || std::atoi(digits.c_str()) > kMaxAlgebraicDegree)
    {
      this->fail("degree above " + std::to_string(kMaxAlgebraicDegree), exponentAt);
    }
    this->Position = end;
    Polynomial3<double> p = constant(1.0);
    for (int k = std::atoi(digits.c_str()); k > 0; --k)
    {
      p = this->checked(multiply(p, base), at);
    }
    return p;
  }

  Polynomial3<double> primary()
  {
    this->skipSpace();
    if (this->Position >= this->Text.size())
    {
      this->fail("unexpected end of the expression");
    }
    const size_t open = this->Position;
    if (this->accept('('))
    {
      Polynomial3<double> p = this->deeper(open, [this] { return this->sum(); });
      if (!this->accept(')'))
      {
        this->fail("'(' at position " + std::to_string(open + 1) + " is not closed");
      }
      return p;
    }
    const char c = this->Text[this->Position];
    if (this->isAt('d', this->Position) || c == '.')
    {
      return constant(this->number());
    }
    if (!this->isAt('a', this->Position) && c != '_')
    {
      this->fail(std::string("unexpected '") + c + "'");
    }
    size_t end = this->Position;
    while (this->isAt('m', end) || (end < this->Text.size() && this->Text[end] == '_'))
    {
      ++end;
    }
    const std::string name = this->Text.substr(this->Position, end - this->Position);
    if (name != "x" && name != "y" && name != "z")
    {
      this->fail("unknown variable '" + name + "' (x, y and z are known)");
    }
    this->Position = end;
    const int d = name[0] - 'x';
    Polynomial3<double> p(d == 0 ? 1 : 0, d == 1 ? 1 : 0, d == 2 ? 1 : 0);
    p.at(d == 0, d == 1, d == 2) = 1.0;
    return p;
  }

  double number()
  {
    const char* start = this->Text.c_str() + this->Position;
    char* end = nullptr;
    const double v = std::strtod(start, &end);
    if (end == start || !std::isfinite(v))
    {
      this->fail("bad number");
    }
    this->Position += size_t(end - start);
    return v;
  }
};
} // namespace detail

/// The polynomial a text describes; std::invalid_argument naming the position otherwise. Degrees
/// above kMaxAlgebraicDegree, in any variable or in total, are refused.
inline Polynomial3<double> parsePolynomial(const std::string& text)
{
  Polynomial3<double> p = detail::ExpressionParser(text).parse();
  if (detail::totalDegree(p) > kMaxAlgebraicDegree)
  {
    throw std::invalid_argument("expression: total degree " +
                                std::to_string(detail::totalDegree(p)) + " above " +
                                std::to_string(kMaxAlgebraicDegree));
  }
  return p;
}

/// The Bernstein volume of the polynomial over the box (x0, x1, y0, y1, z0, z1), its degree per
/// direction the polynomial's (at least 1), with one attribute, the polynomial: the exact
/// volume whose zero set is the algebraic surface, with affine geometry. std::invalid_argument
/// for a box that is not finite or empty in a direction, and for coefficients that overflow.
inline BezierVolume<double> makeAlgebraicVolume(const Polynomial3<double>& field, const double* box)
{
  const char axis[] = "xyz";
  double lo[3], hi[3];
  int degree[3];
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = box[2 * d];
    hi[d] = box[2 * d + 1];
    if (!std::isfinite(lo[d]) || !std::isfinite(hi[d]) || !(lo[d] < hi[d]))
    {
      throw std::invalid_argument(std::string("box: ") + axis[d] + " from " +
                                  std::to_string(lo[d]) + " to " + std::to_string(hi[d]) +
                                  " is not a finite interval");
    }
    degree[d] = std::max(1, field.degree[d]);
  }
  BezierVolume<double> volume = makePolynomialVolume(field, lo, hi, degree);
  for (double c : volume.coeffs())
  {
    if (!std::isfinite(c))
    {
      throw std::invalid_argument("expression: its Bernstein coefficients over the box overflow");
    }
  }
  return volume;
}

} // namespace iga
