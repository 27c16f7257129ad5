#include "image_codec_loader.h"

#include "exr_codec.h"

#include <kdray/error.h>
#include <kdray/module.h>
#include <kdray/util.h>

#include <future>
#include <mutex>

namespace kdray {
namespace {

struct LoadedCodec {
  const ImageCodec* codec = nullptr;
  std::string problem;  // why it could not be loaded
};

LoadedCodec load_codec() {
  LoadedCodec loaded;
  using Entry = const ImageCodec* (*)();
  auto entry = reinterpret_cast<Entry>(
      load_module_symbol("kdray_image_codec.so", "KDRAY_IMAGE_CODEC", "kdray_image_codec", loaded.problem));
  if (entry != nullptr) loaded.codec = entry();
  return loaded;
}

// The load, started once by whichever comes first: a preload (on its own thread) or a use (in
// the caller's thread, when it asks for the result).
const std::shared_future<LoadedCodec>& codec_load(std::launch policy) {
  static std::once_flag once;
  static std::shared_future<LoadedCodec> load;
  std::call_once(once, [policy] { load = std::async(policy, load_codec).share(); });
  return load;
}

// By name, as OpenImageIO picks a writer: a file of another name holding EXR is the module's.
bool handled_by_openexr(const std::string& path) { return lowercase_extension(path) == ".exr"; }

}  // namespace

void start_loading_image_codec(const std::string& path) {
  if (!handled_by_openexr(path)) codec_load(std::launch::async);
}

const ImageCodec& image_codec(const std::string& path) {
  if (handled_by_openexr(path)) return exr_codec();
  const LoadedCodec& loaded = codec_load(std::launch::deferred).get();
  if (loaded.codec == nullptr) throw Error(path, "image files cannot be read or written: " + loaded.problem);
  return *loaded.codec;
}

}  // namespace kdray
