// The header of the partial images geocold-cl writes (--samples, --checkpoint-every): what
// says which frame they belong to. Its chunks are left empty.
#pragma once

#include "host/image/film.h"
#include "host/render/chunks.h"
#include "host/render/partial_image.h"
#include "host/render/render_settings.h"
#include "host/render/session.h"

namespace gc {

PartialImage partial_image_header(const PreparedScene& prepared, const RenderSettings& settings,
                                  const ChunkPlan& plan, const ImageMetadata& meta);

}  // namespace gc
