// igaImageCoverage IMAGE COVERED MINIMUM [overlay|colour-bar]: counts the pixels of a PNG written
// by igaview that differ from the background and checks them against the pixels the engine said it
// covered. The background is a vertical gradient, so each row's is its first pixel's colour (the
// commands under test leave the image's left column empty). Exits 0 when COVERED is at least
// MINIMUM and the count is within 1 % (and 3 pixels) of it, or with "overlay" (text drawn over the
// image adds pixels) at least that; 1 otherwise, saying why. "colour-bar" is "overlay" and also
// wants igaview's colour bar in the image's right fifth: strongly blue and strongly red pixels
// (blue or red above the other by 100), the two ends of its cool-to-warm map.
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv)
{
  const std::string mode = argc == 5 ? argv[4] : "";
  if (argc != 4 && !(argc == 5 && (mode == "overlay" || mode == "colour-bar")))
  {
    std::fprintf(stderr, "usage: igaImageCoverage IMAGE COVERED MINIMUM [overlay|colour-bar]\n");
    return 2;
  }
  const long covered = std::atol(argv[2]), minimum = std::atol(argv[3]);
  const bool overlay = argc == 5;
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(argv[1]))
  {
    std::fprintf(stderr, "igaImageCoverage: cannot read '%s'\n", argv[1]);
    return 1;
  }
  reader->SetFileName(argv[1]);
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int size[3];
  image->GetDimensions(size);
  const int components = image->GetNumberOfScalarComponents();
  const auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  long foreground = 0;
  bool barEnds[2] = { false, false }; // blue, red
  for (int j = 0; j < size[1]; ++j)
  {
    const unsigned char* row = pixels + size_t(j) * size[0] * components;
    for (int i = 1; i < size[0]; ++i)
    {
      bool differs = false;
      for (int c = 0; c < 3; ++c)
      {
        differs = differs || std::abs(int(row[i * components + c]) - int(row[c])) > 2;
      }
      foreground += differs ? 1 : 0;
      if (i > 4 * size[0] / 5)
      {
        const int redOverBlue = int(row[i * components]) - int(row[i * components + 2]);
        barEnds[0] = barEnds[0] || redOverBlue < -100;
        barEnds[1] = barEnds[1] || redOverBlue > 100;
      }
    }
  }
  std::printf("igaImageCoverage: %ld pixels off the background, %ld covered by the engine\n",
    foreground, covered);
  const long slack = covered / 100 > 3 ? covered / 100 : 3;
  if (covered < minimum)
  {
    std::fprintf(
      stderr, "igaImageCoverage: %ld pixels covered, fewer than %ld\n", covered, minimum);
    return 1;
  }
  if (overlay ? foreground < covered - slack : std::labs(foreground - covered) > slack)
  {
    std::fprintf(stderr, "igaImageCoverage: the image shows %ld pixels, the engine covered %ld\n",
      foreground, covered);
    return 1;
  }
  if (mode == "colour-bar" && !(barEnds[0] && barEnds[1]))
  {
    std::fprintf(stderr, "igaImageCoverage: no colour bar in the image's right fifth\n");
    return 1;
  }
  return 0;
}
