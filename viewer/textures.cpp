// SPDX-License-Identifier: MIT
#include "textures.hpp"

#ifndef __EMSCRIPTEN__  // the web build decodes with stb_image (viewer/web/images.cpp)
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "tangent/output.hpp"
#endif

#ifndef __EMSCRIPTEN__
#include <unistd.h>
#endif

#include <algorithm>
#include <span>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tangent/gltf.hpp"
#include "tangent/input_file.hpp"
#include "tangent/text.hpp"

namespace tangent::viewer {

bool checkImageFile(const gltf::ImageSource& source, std::string& error) {
  if (!source.bytes.empty()) return true;
  if (source.file.empty()) {
    error = source.label + ": no image data" + (source.missing.empty() ? " (no URI and no buffer view in range)" : ": " + source.missing);
    return false;
  }
  // The rule's message begins with the file's path; the label names it too (and the glTF image).
  const std::string prefix = source.label == source.file.string() ? "" : source.label + ": ";
  try {
    if (gltf::requireInputFile(source.file, "an image") > 0) return true;
    error = prefix + source.file.string() + ": is empty (0 bytes), not an image";
  } catch (const gltf::InputError& e) {
    error = prefix + e.what();
  }
  return false;
}

#ifndef __EMSCRIPTEN__
namespace {

// What libpng (inside OpenImageIO's PNG reader) writes to stderr on its own ("libpng warning:
// iCCP: known incorrect sRGB profile"), caught while an image is decoded: stderr (fd 2) goes to
// a temporary file from construction to finish(), and each line comes back as a note naming
// the image, so that it reaches the terminal only escaped, through the note channel.
class StderrCapture {
 public:
  StderrCapture() {
    std::fflush(stderr);
    file_ = std::tmpfile();
    if (!file_) return;
    saved_ = dup(2);
    if (saved_ < 0 || dup2(fileno(file_), 2) < 0) {
      if (saved_ >= 0) close(saved_);
      saved_ = -1;
    }
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;
  ~StderrCapture() { restore(); }

  // The captured lines, each as "<label>: <line>" (empty lines dropped, at most 20).
  std::vector<std::string> finish(const std::string& label) {
    std::vector<std::string> lines;
    if (!restore()) return lines;
    std::rewind(file_);
    std::string text;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, file_)) > 0 && text.size() < (1u << 16);) text.append(buffer, n);
    std::fclose(file_);
    file_ = nullptr;
    for (std::size_t start = 0; start < text.size() && lines.size() < 20;) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      if (end > start) lines.push_back(label + ": decoder says: " + text::quoted(text.substr(start, end - start)));
      start = end + 1;
    }
    return lines;
  }

 private:
  // Puts stderr back; false when nothing was captured.
  bool restore() {
    if (saved_ < 0) {
      if (file_) std::fclose(file_), file_ = nullptr;
      return false;
    }
    std::fflush(stderr);
    dup2(saved_, 2);
    close(saved_);
    saved_ = -1;
    return file_ != nullptr;
  }

  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

std::string extensionFor(const std::string& mimeType) {
  if (mimeType == "image/jpeg") return ".jpg";
  if (mimeType == "image/webp") return ".webp";
  if (mimeType == "image/ktx2") return ".ktx2";
  return ".png";
}

// Why an image of this header cannot be decoded here, or "" when it can: no pixels, a volume,
// or more decoded bytes than kMaxDecodedImageBytes.
std::string refusal(const OIIO::ImageSpec& spec) {
  if (spec.width <= 0 || spec.height <= 0) return "has no pixels (" + std::to_string(spec.width) + " x " + std::to_string(spec.height) + ")";
  if (spec.depth > 1) return "is a volume (depth " + std::to_string(spec.depth) + "), not a 2D texture";
  const std::uint64_t bytes = std::uint64_t(spec.width) * std::uint64_t(spec.height) * 4;
  if (bytes <= kMaxDecodedImageBytes) return "";
  char size[64];
  std::snprintf(size, sizeof size, "%.1f GiB", static_cast<double>(bytes) / double(std::uint64_t(1) << 30));
  return "its header claims " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels, " + size +
         " decoded, over the viewer's limit of " + std::to_string(kMaxDecodedImageBytes >> 30) + " GiB; not decoded";
}

// The pixels of an image that checkImageFile allowed (decodeImage's work).
bool decodePixels(const gltf::ImageSource& source, DecodedImage& image, std::string& error) {
  std::unique_ptr<OIIO::ImageInput> input;
  OIIO::Filesystem::IOMemReader memory(source.bytes.data(), source.bytes.size());
  // glTF's alpha is straight (unassociated): keep colour as stored, not premultiplied.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  if (!source.bytes.empty()) {
    // With a configuration given, OIIO takes the proxy from it, not from the third argument.
    OIIO::Filesystem::IOProxy* proxy = &memory;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    input = OIIO::ImageInput::open("embedded" + extensionFor(source.mimeType), &config, &memory);
  } else if (!source.file.empty()) {
    input = OIIO::ImageInput::open(source.file.string(), &config);
  }
  if (!input) {
    const std::string why = OIIO::geterror();
    error = source.label + ": cannot be decoded: " + (why.empty() ? "not in an image format OpenImageIO reads" : why);
    return false;
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (const std::string why = refusal(spec); !why.empty()) {
    error = source.label + ": " + why;
    return false;
  }
  // At most four channels are read: RGBA.
  const int width = spec.width, height = spec.height, channels = std::clamp(spec.nchannels, 1, 4);
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height * channels);
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data())) {
    error = source.label + ": cannot be read: " + input->geterror();
    return false;
  }
  input->close();
  image.width = width;
  image.height = height;
  image.rgba.assign(static_cast<std::size_t>(width) * height * 4, 255);
  // Grey (1 channel) and grey + alpha (2 channels, PNG's colour type 4): the grey into R, G and
  // B, the alpha into A.
  const bool grey = channels <= 2;
  for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p) {
    const unsigned char* texel = &pixels[p * channels];
    unsigned char* out = &image.rgba[4 * p];
    if (grey) {
      out[0] = out[1] = out[2] = texel[0];
      if (channels == 2) out[3] = texel[1];
    } else {
      std::copy_n(texel, channels, out);
    }
  }
  return true;
}

}  // namespace

bool decodeImage(const gltf::ImageSource& source, DecodedImage& image, std::string& error) {
  if (!checkImageFile(source, error)) return false;
  StderrCapture decoderOutput;
  const bool decoded = decodePixels(source, image, error);
  image.notes = decoderOutput.finish(source.label);
  return decoded;
}

// A resampled copy of the image at width x height (false where it cannot be made).
bool resizeImage(const DecodedImage& image, int width, int height, std::vector<unsigned char>& rgba) {
  const OIIO::ImageBuf source(OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::UINT8),
                              const_cast<unsigned char*>(image.rgba.data()));  // wrapped, only read
  const OIIO::ImageBuf resized = OIIO::ImageBufAlgo::resize(source, "", 0.0f, OIIO::ROI(0, width, 0, height, 0, 1, 0, 4));
  return !resized.has_error() && resized.get_pixels(OIIO::ROI(0, width, 0, height, 0, 1, 0, 4), OIIO::TypeDesc::UINT8, rgba.data());
}
#endif

std::string fitTextureSize(DecodedImage& image, int maxSize, const std::string& label) {
  if (maxSize <= 0 || (image.width <= maxSize && image.height <= maxSize)) return "";
  const double scale = static_cast<double>(maxSize) / std::max(image.width, image.height);
  const int width = std::clamp(static_cast<int>(std::lround(image.width * scale)), 1, maxSize);
  const int height = std::clamp(static_cast<int>(std::lround(image.height * scale)), 1, maxSize);
  std::vector<unsigned char> rgba(static_cast<std::size_t>(width) * height * 4);
  if (!resizeImage(image, width, height, rgba)) {
    // Keep every n-th texel instead: coarse, but it fits.
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        std::copy_n(&image.rgba[(static_cast<std::size_t>(y) * image.height / height * image.width +
                                 static_cast<std::size_t>(x) * image.width / width) * 4],
                    4, &rgba[(static_cast<std::size_t>(y) * width + x) * 4]);
  }
  std::string note = label + ": " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                     " pixels, over this GL's largest texture (" + std::to_string(maxSize) + "); shown downscaled to " +
                     std::to_string(width) + " x " + std::to_string(height);
  image.width = width;
  image.height = height;
  image.rgba = std::move(rgba);
  return note;
}

int maxTextureSize() {
  GLint size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &size);
  return size;
}

Texture uploadTexture(const DecodedImage& image, bool srgb) {
  Texture texture = makeTexture();
  glBindTexture(GL_TEXTURE_2D, texture.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // glTF's UV origin is the image's first row: upload rows as stored, sample uv as given.
  glTexImage2D(GL_TEXTURE_2D, 0, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               image.rgba.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return texture;
}

DecodedImage missingImageChecker() {
  DecodedImage image;
  image.width = image.height = kMissingImageCellTexels * kMissingImageCells;
  image.rgba.resize(static_cast<std::size_t>(image.width) * image.height * 4);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool magenta = (x / kMissingImageCellTexels + y / kMissingImageCellTexels) % 2 == 0;
      unsigned char* texel = &image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4];
      texel[0] = magenta ? 255 : 16;
      texel[1] = magenta ? 0 : 16;
      texel[2] = magenta ? 255 : 16;
      texel[3] = 255;
    }
  }
  return image;
}

Texture loadTexture(const gltf::ImageSource& source, bool srgb, std::vector<std::string>& messages) {
  DecodedImage image;
  std::string error;
  const bool decoded = decodeImage(source, image, error);
  messages.insert(messages.end(), image.notes.begin(), image.notes.end());
  if (!decoded) {
    messages.push_back(error);
    return {};
  }
  if (std::string note = fitTextureSize(image, maxTextureSize(), source.label); !note.empty()) messages.push_back(std::move(note));
  return uploadTexture(image, srgb);
}

#ifndef __EMSCRIPTEN__
bool writePng(const std::string& path, int width, int height, const std::vector<unsigned char>& rgbaBottomUp, std::string& error) {
  // Encoded in memory, then written as every output of this project is (output.hpp): atomically
  // where `path` is a regular file, in place where it is a device or FIFO, refused otherwise.
  auto out = OIIO::ImageOutput::create("png");
  if (!out || !out->supports("ioproxy")) {
    error = path + ": no PNG encoder that writes to memory: " + OIIO::geterror();
    return false;
  }
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
  OIIO::Filesystem::IOProxy* proxy = &memory;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (!out->open(path, spec)) {
    error = path + ": " + out->geterror();
    return false;
  }
  const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(width) * 4;
  // Start at the last row and step backwards: top-down image from bottom-up pixels.
  const bool ok = out->write_image(OIIO::TypeDesc::UINT8, rgbaBottomUp.data() + row * (height - 1), 4, -row);
  if (!out->close() || !ok) {
    error = path + ": " + out->geterror();
    return false;
  }
  try {
    output::writeFileAtomic(path, {std::span<const std::uint8_t>(encoded.data(), encoded.size())});
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
  return true;
}

#endif

}  // namespace tangent::viewer
