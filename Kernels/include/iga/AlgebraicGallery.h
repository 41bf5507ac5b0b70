// The algebraic surfaces of Reimers and Seland's and Seland and Dokken's studies, as polynomial
// expressions with a box around the part worth seeing. Equations from MathWorld's entries
// (Cayley cubic, Clebsch diagonal surface, Kummer surface with mu^2 = 1.3, Dervish, tanglecube,
// Kiss surface, Barth decic) and the papers (heart, Klein bottle, linked tori, super-sphere),
// irrational constants written out to double precision; the papers' own tables garble a few
// (Cayley's constant, Clebsch's terms, the tanglecube's 11.8). Tests count the nodes each is
// known for: the Dervish's 31 are all real, 26 of them inside its box here.
#pragma once

#include <string>

namespace iga
{

struct AlgebraicSurface
{
  const char* name;
  const char* expression;
  double box[6]; ///< x0, x1, y0, y1, z0, z1
  int nodes;     ///< singular points inside the box (-1: not counted)
};

inline const AlgebraicSurface* algebraicGallery(int& count)
{
  static const AlgebraicSurface gallery[] = {
    { "sphere", "x^2 + y^2 + z^2 - 1", { -1.2, 1.2, -1.2, 1.2, -1.2, 1.2 }, 0 },
    { "cayley", "4*(x^2 + y^2 + z^2) - 16*x*y*z - 1", { -1, 1, -1, 1, -1, 1 }, 4 },
    { "clebsch",
      "81*(x^3 + y^3 + z^3) - 189*(x^2*y + x^2*z + y^2*x + y^2*z + z^2*x + z^2*y) + 54*x*y*z"
      " + 126*(x*y + x*z + y*z) - 9*(x^2 + y^2 + z^2) - 9*(x + y + z) + 1",
      { -1, 1, -1, 1, -1, 1 }, -1 },
    { "kummer",
      "(x^2 + y^2 + z^2 - 1.3)^2 - 1.7058823529411766*(1 - z - 1.4142135623730951*x)"
      "*(1 - z + 1.4142135623730951*x)*(1 + z + 1.4142135623730951*y)"
      "*(1 + z - 1.4142135623730951*y)",
      { -2.5, 2.5, -2.5, 2.5, -2.5, 2.5 }, 16 },
    { "dervish",
      "64*(x - 1)*(x^4 - 4*x^3 - 10*x^2*y^2 - 4*x^2 + 16*x - 20*x*y^2 + 5*y^4 + 16 - 20*y^2)"
      " - 8.312538755549069*(2*z - 1.6625077511098136)"
      "*(4*(x^2 + y^2 - z^2) + 7.708203932499369)^2",
      { -4, 4, -4, 4, -4, 4 }, 26 },
    { "kiss", "x^2 + y^2 - z^4 + z^5", { -0.5, 0.5, -0.5, 0.5, -0.5, 1 }, -1 },
    { "heart", "(x^2 + 2.25*y^2 + z^2 - 1)^3 - x^2*z^3 - 0.1125*y^2*z^3",
      { -1.5, 1.5, -1, 1, -1.5, 1.5 }, -1 },
    { "klein",
      "(x^2 + y^2 + z^2 + 2*y - 1)*((x^2 + y^2 + z^2 - 2*y - 1)^2 - 8*z^2)"
      " + 16*x*z*(x^2 + y^2 + z^2 - 2*y - 1)",
      { -3, 3, -3.5, 3.5, -2.5, 2.5 }, -1 },
    { "linked-tori",
      "((100*x^2 + (10*y - 2)^2 + 100*z^2 + 13)^2 - 53*(100*x^2 + (10*y - 2)^2))"
      "*((100*z^2 + (10*y + 2)^2 + 100*x^2 + 13)^2 - 53*(100*z^2 + (10*y + 2)^2)) + 1000",
      { -0.6, 0.6, -0.6, 0.6, -0.6, 0.6 }, -1 },
    { "tangle", "x^4 - 5*x^2 + y^4 - 5*y^2 + z^4 - 5*z^2 + 11.8",
      { -2.5, 2.5, -2.5, 2.5, -2.5, 2.5 }, 0 },
    { "barth-decic",
      "8*(x^2 - 6.854101966249686*y^2)*(y^2 - 6.854101966249686*z^2)"
      "*(z^2 - 6.854101966249686*x^2)"
      "*(x^4 + y^4 + z^4 - 2*x^2*y^2 - 2*x^2*z^2 - 2*y^2*z^2)"
      " + 11.090169943749475*(x^2 + y^2 + z^2 - 1)^2*(x^2 + y^2 + z^2 - 0.3819660112501051)^2",
      { -1.5, 1.5, -1.5, 1.5, -1.5, 1.5 }, -1 },
    { "super-sphere", "x^16 + y^16 + z^16 - 0.0001", { -0.7, 0.7, -0.7, 0.7, -0.7, 0.7 }, -1 },
  };
  count = int(sizeof(gallery) / sizeof(gallery[0]));
  return gallery;
}

/// The gallery's surface of that name, or null.
inline const AlgebraicSurface* findAlgebraicSurface(const std::string& name)
{
  int count = 0;
  const AlgebraicSurface* gallery = algebraicGallery(count);
  for (int k = 0; k < count; ++k)
  {
    if (name == gallery[k].name)
    {
      return &gallery[k];
    }
  }
  return nullptr;
}

} // namespace iga
