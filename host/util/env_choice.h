// Environment variables that pick one of a few named choices (GEOCOLD_PATH_KERNEL,
// GEOCOLD_BVH_WIDTH, GEOCOLD_KERNEL_FEATURES): unset or empty means "the default", anything
// outside the list is a usage error naming the variable, what it may be and what it was.
#pragma once

#include <cstdlib>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "host/util/error.h"

namespace gc {

// The value of `name` when set, after checking it is one of `allowed`; nullopt when unset or
// empty. `allowed_text` is how the message lists the choices, e.g. "'scene' or 'all'".
inline std::optional<std::string> env_choice(const char* name, std::initializer_list<std::string_view> allowed,
                                             const char* allowed_text)
{
    const char* env = std::getenv(name);
    if (!env || !*env) return std::nullopt;
    const std::string value(env);
    for (const std::string_view a : allowed)
        if (value == a) return value;
    throw UsageError(std::string(name) + " must be " + allowed_text + ", not '" + value + "'");
}

}  // namespace gc
