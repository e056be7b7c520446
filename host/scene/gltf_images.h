// Decoding of glTF images (embedded, data: URI or external file) for tinygltf, with the checks
// tinygltf 2.7 leaves out.
#pragma once

namespace tinygltf {
class TinyGLTF;
class Model;
}  // namespace tinygltf

namespace gc {

// Largest decoded image accepted: 16384 texels on a side and 2^27 texels in all (512 MiB as
// RGBA8). A few bytes of PNG or JPEG header can claim gigapixels; stb_image would try to
// allocate them before finding out the data is not there.
inline constexpr int k_max_image_side = 16384;
inline constexpr long long k_max_image_texels = 1ll << 27;

// Makes `loader` decode images with stb_image through our callback instead of tinygltf's own.
// tinygltf resolves an embedded image's bufferView and buffer indices but hands the decoder
// &buffer.data[byteOffset] with byteLength bytes without checking that range against the
// buffer, so a hostile file makes stb_image read past the heap block. The callback looks the
// bufferView up again in `model` (buffers and bufferViews are parsed before images, so they
// are in place by then) and refuses a range that leaves its buffer, before any byte is read.
// `model` must be the model the loader fills, and must outlive the load call.
void install_checked_image_decoder(tinygltf::TinyGLTF& loader, const tinygltf::Model& model);

}  // namespace gc
