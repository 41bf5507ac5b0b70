// igaImageCoverage IMAGE COVERED MINIMUM [overlay]: counts the pixels of a PNG written by
// igaview that differ from the background and checks them against the pixels the engine said
// it covered. The background is a vertical gradient, so each row's is its first pixel's colour
// (the commands under test leave the image's left column empty). Exits 0 when COVERED is at
// least MINIMUM and the count is within 1 % (and 3 pixels) of it, or with "overlay" (text drawn
// over the image adds pixels) at least that; 1 otherwise, saying why.
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv)
{
  if (argc != 4 && !(argc == 5 && std::string(argv[4]) == "overlay"))
  {
    std::fprintf(stderr, "usage: igaImageCoverage IMAGE COVERED MINIMUM [overlay]\n");
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
  return 0;
}
