#include "png_image.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

namespace pcl_ncut_seg {

bool readPng(const std::string& path, RgbImage& image) {
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str()))
    return false;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* data = reader->GetOutput();
  if (!data || data->GetScalarType() != VTK_UNSIGNED_CHAR)
    return false;
  int dims[3];
  data->GetDimensions(dims);
  const int channels = data->GetNumberOfScalarComponents();
  if (dims[0] <= 0 || dims[1] <= 0 || channels < 1)
    return false;
  image.width = dims[0];
  image.height = dims[1];
  image.rgb.resize(static_cast<std::size_t>(dims[0]) * dims[1] * 3);
  const auto* px = static_cast<const unsigned char*>(data->GetScalarPointer());
  // VTK's rows run from the bottom up.
  for (int y = 0; y < dims[1]; ++y)
    for (int x = 0; x < dims[0]; ++x) {
      const unsigned char* in = px + (static_cast<std::size_t>(y) * dims[0] + x) * channels;
      std::uint8_t* out = &image.rgb[(static_cast<std::size_t>(dims[1] - 1 - y) * dims[0] + x) * 3];
      for (int c = 0; c < 3; ++c)
        out[c] = in[channels >= 3 ? c : 0];
    }
  return true;
}

} // namespace pcl_ncut_seg
