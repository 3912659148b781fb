#include "io/npy.h"

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <numeric>
#include <string>

#include "core/error.h"

namespace fovrt {
namespace {

constexpr char kMagic[] = "\x93NUMPY";

int64_t Count(const std::vector<int64_t>& shape) {
    return std::accumulate(shape.begin(), shape.end(), int64_t(1), std::multiplies<int64_t>());
}

}  // namespace

void WriteNpy(const std::filesystem::path& path, const NpyArray& array) {
    if (Count(array.shape) != int64_t(array.data.size()))
        Fail("{}: shape holds {} values, data {}", path.string(), Count(array.shape), array.data.size());
    std::string shape;
    for (int64_t d : array.shape) shape += fmt::format("{}, ", d);
    if (array.shape.size() > 1) shape.resize(shape.size() - 2);  // (n,) keeps its comma
    std::string header = fmt::format("{{'descr': '<f4', 'fortran_order': False, 'shape': ({}), }}", shape);
    // Magic (6) + version (2) + length (2) + header + '\n' padded to a multiple of 64.
    size_t total = 10 + header.size() + 1;
    header.append((64 - total % 64) % 64, ' ');
    header.push_back('\n');
    const std::filesystem::path tmp = path.string() + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary);
        if (!f) Fail("{}: cannot write", tmp.string());
        f.write(kMagic, 6);
        const char version[2] = {1, 0};
        f.write(version, 2);
        const uint16_t len = uint16_t(header.size());
        const char lenBytes[2] = {char(len & 0xFF), char(len >> 8)};
        f.write(lenBytes, 2);
        f.write(header.data(), std::streamsize(header.size()));
        f.write(reinterpret_cast<const char*>(array.data.data()), std::streamsize(array.data.size() * 4));
        if (!f) Fail("{}: write failed", tmp.string());
    }
    std::filesystem::rename(tmp, path);
}

NpyArray ReadNpy(const std::filesystem::path& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) Fail("{}: cannot open", path.string());
    char head[10];
    f.read(head, 10);
    if (!f || std::memcmp(head, kMagic, 6) != 0) Fail("{}: not a .npy file", path.string());
    size_t len = 0, skip = 10;
    if (head[6] == 1) {
        len = uint8_t(head[8]) | size_t(uint8_t(head[9])) << 8;
    } else {  // versions 2 and 3: 4-byte header length
        char more[2];
        f.read(more, 2);
        len = uint8_t(head[8]) | size_t(uint8_t(head[9])) << 8 | size_t(uint8_t(more[0])) << 16 |
              size_t(uint8_t(more[1])) << 24;
        skip = 12;
    }
    (void)skip;
    std::string header(len, '\0');
    f.read(header.data(), std::streamsize(len));
    if (header.find("'<f4'") == std::string::npos)
        Fail("{}: only little-endian float32 ('<f4') arrays are read: {}", path.string(), header);
    if (header.find("'fortran_order': False") == std::string::npos)
        Fail("{}: only C-order arrays are read", path.string());
    const size_t open = header.find('(', header.find("'shape'"));
    const size_t close = header.find(')', open);
    if (open == std::string::npos || close == std::string::npos) Fail("{}: no shape in header", path.string());
    NpyArray a;
    std::string dims = header.substr(open + 1, close - open - 1);
    size_t pos = 0;
    while (pos < dims.size()) {
        size_t comma = dims.find(',', pos);
        std::string token = dims.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
        if (token.find_first_not_of(' ') != std::string::npos) a.shape.push_back(std::stoll(token));
        if (comma == std::string::npos) break;
        pos = comma + 1;
    }
    a.data.resize(size_t(Count(a.shape)));
    f.read(reinterpret_cast<char*>(a.data.data()), std::streamsize(a.data.size() * 4));
    if (!f) Fail("{}: truncated ({} values expected)", path.string(), a.data.size());
    return a;
}

}  // namespace fovrt
