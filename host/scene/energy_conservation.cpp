#include "host/scene/energy_conservation.h"

namespace gc {

bool enforce_energy_conservation(Material& material)
{
    bool changed = false;
    for (int c = 0; c < 3; ++c) {
        const float sum = material.albedo[c] + material.specular[c];
        if (sum > 1.0f) {
            material.albedo[c] /= sum;
            material.specular[c] /= sum;
            changed = true;
        }
    }
    return changed;
}

}  // namespace gc
