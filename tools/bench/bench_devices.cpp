#include "tools/bench/bench_devices.h"

namespace gc::bench {

std::string DeviceSlot::label() const
{
    const std::string& p = info.platform_name;
    std::string s = "[";
    s += std::to_string(index);
    s += "] ";
    s += p.find("Portable") != std::string::npos ? std::string("PoCL") : p.substr(0, p.find(' '));
    s += " ";
    s += info.type_name();
    return s;
}

std::vector<DeviceSlot> selected_devices(const Options& o, const std::vector<cl::DeviceInfo>& all)
{
    std::vector<DeviceSlot> devices;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (o.device != "all" && cl::select_device(o.device, all).id != all[i].id) continue;
        DeviceSlot slot;
        slot.index = static_cast<int>(i);
        slot.info = all[i];
        devices.push_back(std::move(slot));
    }
    return devices;
}

}  // namespace gc::bench
