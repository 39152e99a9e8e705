#include "netcdf_precheck.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "ibfvs/core/support/error.h"

namespace ibfvs::detail {
namespace {

// The header's tags (netCDF classic format specification).
constexpr std::uint32_t kDimensionTag = 0x0A;
constexpr std::uint32_t kVariableTag = 0x0B;
constexpr std::uint32_t kAttributeTag = 0x0C;
constexpr std::uint64_t kMaxName = 256;      // NC_MAX_NAME
constexpr std::uint64_t kMaxVarDims = 1024;  // NC_MAX_VAR_DIMS

// Bytes per value of an nc_type (1 byte .. 6 double; 7-11 in CDF-5 only);
// 0 for a type the version does not have.
std::uint64_t type_size(std::uint32_t type, int version) {
  static constexpr std::array<std::uint64_t, 12> kSizes{0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8};
  if (type == 0 || type > (version == 5 ? 11u : 6u)) return 0;
  return kSizes[type];
}

class HeaderWalk {
 public:
  HeaderWalk(const std::filesystem::path& path, std::ifstream& in, std::uint64_t size, int version)
      : path_(path), in_(in), size_(size), version_(version) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(one_line(path_.string() + ": not a valid netCDF file: " + problem +
                              " (header byte " + std::to_string(at_) + ")"));
  }

  // The data a variable's header points at run past the end of the file.
  [[noreturn]] void cut_short(const std::string& var, std::uint64_t needs) const {
    // one_line: names are the file's bytes.
    throw InputError(one_line(path_.string() + ": the file is cut short: variable '" + var +
                              "' needs " +
                              (needs == 0 ? std::string("more") : std::to_string(needs)) +
                              " bytes, the file has " + std::to_string(size_)));
  }

  std::uint64_t remaining() const { return size_ - at_; }

  std::uint64_t big_endian(int bytes, const char* what) {
    if (remaining() < static_cast<std::uint64_t>(bytes)) fail(std::string("it ends in ") + what);
    std::array<unsigned char, 8> b{};
    in_.read(reinterpret_cast<char*>(b.data()), bytes);
    if (!in_) fail(std::string("it cannot be read at ") + what);
    at_ += static_cast<std::uint64_t>(bytes);
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | b[static_cast<std::size_t>(i)];
    return v;
  }
  std::uint32_t u32(const char* what) { return static_cast<std::uint32_t>(big_endian(4, what)); }
  // NON_NEG: 4 bytes, 8 in CDF-5; a 4-byte one is a signed int, at most 2^31-1.
  std::uint64_t non_negative(const char* what) {
    const std::uint64_t v = big_endian(version_ == 5 ? 8 : 4, what);
    if (v > (version_ == 5 ? 0x7FFFFFFFFFFFFFFFull : 0x7FFFFFFFull))
      fail(std::string("a negative ") + what);
    return v;
  }
  void skip(std::uint64_t bytes, const char* what) {
    if (bytes > remaining()) fail(std::string(what) + " runs past the end of the file");
    in_.seekg(static_cast<std::streamoff>(bytes), std::ios::cur);
    at_ += bytes;
  }

  // A list's tag and count: absent (both zero) gives 0. Each element takes
  // at least `least` bytes, so a count the rest of the file cannot hold is
  // refused before netCDF-C allocates for it.
  std::uint64_t list(std::uint32_t tag, std::uint64_t least, const char* what) {
    const std::uint32_t t = u32(what);
    const std::uint64_t n = non_negative(what);
    if (t == 0 && n == 0) return 0;
    if (t != tag) fail(std::string("a bad tag for its ") + what);
    if (n > remaining() / least)
      fail("it declares " + std::to_string(n) + " " + what + ", more than the file could hold");
    return n;
  }

  std::string name(const char* what) {
    const std::uint64_t n = non_negative(what);
    if (n == 0 || n > kMaxName)
      fail(std::string("a ") + what + " of " + std::to_string(n) +
           " characters (1 to 256 allowed)");
    if (n > remaining()) fail(std::string("a ") + what + " runs past the end of the file");
    std::string text(n, '\0');
    in_.read(text.data(), static_cast<std::streamsize>(n));
    at_ += n;
    skip((4 - n % 4) % 4, what);
    return text;
  }

  void attributes() {
    const std::uint64_t count = list(kAttributeTag, 16, "attributes");
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::string attribute = name("attribute name");
      const std::uint64_t size = type_size(u32("attribute type"), version_);
      if (size == 0) fail("attribute '" + attribute + "' has an unknown type");
      const std::uint64_t values = non_negative("attribute length");
      if (values > remaining() / size)
        fail("attribute '" + attribute + "' runs past the end of the file");
      const std::uint64_t bytes = values * size;
      skip(bytes + (4 - bytes % 4) % 4, "an attribute");
    }
  }

  void walk() {
    const std::uint64_t records = big_endian(version_ == 5 ? 8 : 4, "record count");
    const bool streaming = records == (version_ == 5 ? UINT64_MAX : 0xFFFFFFFFull);
    const int word = version_ == 5 ? 8 : 4;
    const std::uint64_t dims = list(kDimensionTag, 4 + 2 * word, "dimensions");
    std::vector<std::uint64_t> lengths;
    bool unlimited = false;
    for (std::uint64_t i = 0; i < dims; ++i) {
      const std::string dim = name("dimension name");
      lengths.push_back(non_negative("dimension length"));
      if (lengths.back() == 0) {
        if (unlimited) fail("more than one unlimited dimension");
        unlimited = true;
      }
    }
    attributes();
    struct RecordVar {
      std::string name;
      std::uint64_t begin, bytes;  // first record's offset, one record's bytes
    };
    std::vector<RecordVar> record_vars;
    const std::uint64_t vars = list(kVariableTag, 4 * 4 + 3 * word, "variables");
    for (std::uint64_t v = 0; v < vars; ++v) {
      const std::string var = name("variable name");
      const std::uint64_t rank = non_negative("variable rank");
      if (rank > kMaxVarDims)
        fail("variable '" + var + "' has " + std::to_string(rank) + " dimensions (at most 1024)");
      if (rank > remaining() / static_cast<std::uint64_t>(word))
        fail("variable '" + var + "' runs past the end of the file");
      bool record = false;
      std::uint64_t values = 1;
      bool overflow = false;
      for (std::uint64_t k = 0; k < rank; ++k) {
        const std::uint64_t id = non_negative("dimension id");
        if (id >= lengths.size())
          fail("variable '" + var + "' names dimension " + std::to_string(id) + " of " +
               std::to_string(lengths.size()));
        if (lengths[id] == 0) {
          if (k != 0) fail("variable '" + var + "' has the unlimited dimension after the first");
          record = true;
          continue;
        }
        if (values > UINT64_MAX / lengths[id]) overflow = true;
        values *= lengths[id];
      }
      attributes();
      const std::uint64_t size = type_size(u32("variable type"), version_);
      if (size == 0) fail("variable '" + var + "' has an unknown type");
      non_negative("variable size");  // vsize: redundant, and capped for big variables
      const std::uint64_t begin = big_endian(version_ == 1 ? 4 : 8, "variable offset");
      // A variable's data lie inside the file: netCDF-C reads a file cut
      // short as zeros, a silently wrong field. (Sizes beyond 64 bits are
      // refused as not fitting any file.)
      if (overflow || values > UINT64_MAX / size) cut_short(var, 0);
      if (begin > size_) cut_short(var, begin);
      if (!record && values * size > size_ - begin) cut_short(var, begin + values * size);
      if (record) record_vars.push_back({var, begin, values * size});
    }
    // Record variables: record r of each lies at its offset plus r records,
    // a record being every record variable's slice (each padded to 4 bytes
    // unless there is only one).
    if (streaming || records == 0 || record_vars.empty()) return;
    std::uint64_t record_bytes = 0;
    for (const RecordVar& r : record_vars) {
      if (r.bytes > size_) cut_short(r.name, 0);
      record_bytes += record_vars.size() == 1 ? r.bytes : r.bytes + (4 - r.bytes % 4) % 4;
    }
    for (const RecordVar& r : record_vars) {
      if (record_bytes != 0 && records - 1 > (UINT64_MAX - r.begin - r.bytes) / record_bytes)
        cut_short(r.name, 0);
      const std::uint64_t end = r.begin + (records - 1) * record_bytes + r.bytes;
      if (end > size_) cut_short(r.name, end);
    }
  }

 private:
  const std::filesystem::path& path_;
  std::ifstream& in_;
  std::uint64_t size_;
  int version_;
  std::uint64_t at_ = 4;
};

}  // namespace

void precheck_netcdf(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!in || ec) return;  // nc_open says why
  std::array<char, 4> magic{};
  in.read(magic.data(), 4);
  if (!in || magic[0] != 'C' || magic[1] != 'D' || magic[2] != 'F') return;
  const int version = magic[3];
  if (version != 1 && version != 2 && version != 5)
    throw InputError(path.string() + ": not a valid netCDF file: classic format version " +
                     std::to_string(version) + " (1, 2 and 5 exist)");
  HeaderWalk(path, in, size, version).walk();
}

}  // namespace ibfvs::detail
