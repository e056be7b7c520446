#include "host/scene/gltf_conformance.h"

#include <algorithm>
#include <charconv>
#include <limits>

#include <nlohmann/json.hpp>

#include "host/util/error.h"
#include "host/util/log.h"

namespace gc {

namespace {

using Json = nlohmann::json;

struct GltfVersion {
    int major = 0;
    int minor = 0;
};

// A run of decimal digits as a number; one too large for an int reads as INT_MAX, which is
// as unsupported as its true value.
std::optional<int> parse_digits(std::string_view digits)
{
    if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return std::nullopt;
    int value = 0;
    if (std::from_chars(digits.data(), digits.data() + digits.size(), value).ec != std::errc{})
        return std::numeric_limits<int>::max();
    return value;
}

// "MAJOR.MINOR", both decimal digits only (the spec's pattern ^[0-9]+\.[0-9]+$).
std::optional<GltfVersion> parse_version(std::string_view text)
{
    const auto dot = text.find('.');
    if (dot == std::string_view::npos) return std::nullopt;
    const std::optional<int> major = parse_digits(text.substr(0, dot));
    const std::optional<int> minor = parse_digits(text.substr(dot + 1));
    if (!major || !minor) return std::nullopt;
    return GltfVersion{*major, *minor};
}

// Extension names as listed; an entry that is not a string is kept as its JSON, so that it is
// reported rather than silently dropped.
std::vector<std::string> names_in(const Json& list)
{
    std::vector<std::string> names;
    if (!list.is_array()) return {list.dump()};
    for (const Json& entry : list) names.push_back(entry.is_string() ? entry.get<std::string>() : entry.dump());
    return names;
}

// A name or version from the file as a message shows it: a hostile file's control
// characters (terminal escapes) become '?', and a runaway string is cut short.
std::string shown(const std::string& text)
{
    constexpr std::size_t k_max_shown = 64;
    std::string out = text.substr(0, k_max_shown);
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return text.size() > k_max_shown ? out + "..." : out;
}

std::string joined(const std::vector<std::string>& names)
{
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + shown(n);
    return out;
}

std::string supported_list()
{
    return joined(std::vector<std::string>(k_supported_gltf_extensions.begin(), k_supported_gltf_extensions.end()));
}

void check_version(const GltfDeclarations& declared, const std::string& file_name)
{
    if (!declared.version)
        throw InputError(file_name + ": asset.version is missing (a glTF 2.0 asset declares \"2.0\")");
    const std::optional<GltfVersion> version = parse_version(*declared.version);
    const std::string version_shown = shown(*declared.version);
    if (!version) throw InputError(file_name + ": asset.version '" + version_shown + "' is not MAJOR.MINOR");
    if (version->major != 2)
        throw InputError(file_name + ": glTF version " + version_shown +
                         " (asset.version) is not supported; this loader reads glTF 2.x");
    if (!declared.min_version) return;
    const std::optional<GltfVersion> min = parse_version(*declared.min_version);
    const std::string min_shown = shown(*declared.min_version);
    if (!min) throw InputError(file_name + ": asset.minVersion '" + min_shown + "' is not MAJOR.MINOR");
    if (min->major > 2 || (min->major == 2 && min->minor > 0))
        throw InputError(file_name + ": asset.minVersion " + min_shown + " asks for a glTF " + min_shown +
                         " loader; this one implements glTF 2.0");
}

}  // namespace

bool gltf_extension_supported(std::string_view name)
{
    return std::find(k_supported_gltf_extensions.begin(), k_supported_gltf_extensions.end(), name) !=
           k_supported_gltf_extensions.end();
}

std::vector<std::string> unsupported_gltf_extensions(const std::vector<std::string>& names)
{
    std::vector<std::string> out;
    for (const std::string& n : names)
        if (!gltf_extension_supported(n) && std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
    return out;
}

std::optional<GltfDeclarations> read_gltf_declarations(std::string_view json_text)
{
    // Members other than these are discarded as they are parsed: a .gltf can embed its
    // buffers and images as data URIs, and none of that needs to be kept twice.
    const Json::parser_callback_t keep_declarations = [](int depth, Json::parse_event_t event, Json& parsed) {
        if (event != Json::parse_event_t::key || depth != 1) return true;
        const std::string& key = parsed.get_ref<const std::string&>();
        return key == "asset" || key == "extensionsRequired" || key == "extensionsUsed";
    };
    const Json doc = Json::parse(json_text.begin(), json_text.end(), keep_declarations, /*allow_exceptions=*/false);
    if (doc.is_discarded() || !doc.is_object()) return std::nullopt;

    GltfDeclarations declared;
    if (const auto asset = doc.find("asset"); asset != doc.end() && asset->is_object()) {
        if (const auto v = asset->find("version"); v != asset->end() && v->is_string())
            declared.version = v->get<std::string>();
        if (const auto v = asset->find("minVersion"); v != asset->end())
            declared.min_version = v->is_string() ? v->get<std::string>() : v->dump();
    }
    if (const auto list = doc.find("extensionsRequired"); list != doc.end())
        declared.extensions_required = names_in(*list);
    if (const auto list = doc.find("extensionsUsed"); list != doc.end())
        declared.extensions_used = names_in(*list);
    return declared;
}

void check_gltf_declarations(const GltfDeclarations& declared, const std::string& file_name)
{
    check_version(declared, file_name);
    const std::vector<std::string> missing = unsupported_gltf_extensions(declared.extensions_required);
    if (!missing.empty())
        throw InputError(file_name + ": requires glTF extension(s) " + joined(missing) +
                         ", which this loader does not implement (it implements " + supported_list() + ")");
}

void warn_unsupported_gltf_extensions(const std::vector<std::string>& extensions_used, const std::string& file_name)
{
    const std::vector<std::string> ignored = unsupported_gltf_extensions(extensions_used);
    if (!ignored.empty())
        log_warning(file_name + ": uses glTF extension(s) " + joined(ignored) +
                    ", which this loader does not implement; ignored, so the image may differ from the intended one");
}

}  // namespace gc
