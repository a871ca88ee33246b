#include "scenes/ply_check.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

#include "scenes/errors.h"

namespace voxgi {

namespace {

struct ScalarType {
    int bytes;
    bool isSigned;
    bool isFloat;
};

const std::map<std::string, ScalarType>& scalarTypes() {
    static const std::map<std::string, ScalarType> kTypes = {
        {"char", {1, true, false}},   {"uchar", {1, false, false}},  {"int8", {1, true, false}},
        {"uint8", {1, false, false}}, {"short", {2, true, false}},    {"ushort", {2, false, false}},
        {"int16", {2, true, false}},  {"uint16", {2, false, false}}, {"int", {4, true, false}},
        {"uint", {4, false, false}},  {"int32", {4, true, false}},   {"uint32", {4, false, false}},
        {"float", {4, true, true}},   {"float32", {4, true, true}},  {"double", {8, true, true}},
        {"float64", {8, true, true}}};
    return kTypes;
}

struct Property {
    ScalarType value{};
    bool isList = false;
    ScalarType count{};  // a list's count type
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
};

// The file, mapped read-only: the walk touches only the pages it reads.
class MappedFile {
public:
    explicit MappedFile(const std::string& path) {
        const int fd = ::open(path.c_str(), O_RDONLY);
        if (fd < 0) throw InputError(path + ": cannot open mesh file");
        struct stat st {};
        if (::fstat(fd, &st) == 0 && st.st_size > 0) {
            size_ = std::size_t(st.st_size);
            void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
            data_ = p == MAP_FAILED ? nullptr : static_cast<const char*>(p);
        }
        ::close(fd);
        if (!data_) throw InputError(path + ": cannot read mesh file");
    }
    ~MappedFile() { ::munmap(const_cast<char*>(data_), size_); }
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;
    const char* data() const { return data_; }
    std::size_t size() const { return size_; }

private:
    const char* data_ = nullptr;
    std::size_t size_ = 0;
};

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::vector<std::string> splitWords(const char* begin, const char* end) {
    std::vector<std::string> words;
    for (const char* p = begin; p < end;) {
        while (p < end && isBlank(*p)) ++p;
        const char* start = p;
        while (p < end && !isBlank(*p)) ++p;
        if (p > start) words.emplace_back(start, p);
    }
    return words;
}

bool isName(const std::string& s) {
    if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
    return true;
}

// A count written the plain way: decimal digits only, at most 2^32.
bool parseCount(const std::string& s, std::uint64_t& value) {
    if (s.empty() || s.size() > 10) return false;
    value = 0;
    for (char c : s) {
        if (c < '0' || c > '9') return false;
        value = value * 10 + std::uint64_t(c - '0');
    }
    return value <= (std::uint64_t(1) << 32);
}

bool isNumber(const std::string& s) {
    bool digit = false;
    for (char c : s) {
        if (c >= '0' && c <= '9') digit = true;
        else if (!std::strchr("+-.eE", c)) return false;
    }
    return digit;
}

std::uint64_t largestCount(const ScalarType& t) {
    if (t.isFloat) return 0;  // a list counted by a float is refused
    return t.bytes >= 4 ? (std::uint64_t(1) << 32) : (std::uint64_t(1) << (8 * t.bytes - (t.isSigned ? 1 : 0))) - 1;
}

// Header lines into elements; `offset` ends after the end_header line.
std::vector<Element> readHeader(const std::string& path, const MappedFile& file, bool& binary, bool& bigEndian,
                                std::size_t& offset) {
    auto fail = [&](int n, const std::string& why) {
        throw InputError(path + ": PLY header line " + std::to_string(n) + ": " + why);
    };
    std::vector<Element> elements;
    bool formatSeen = false;
    for (int n = 1;; ++n) {
        if (offset >= file.size()) throw InputError(path + ": PLY header has no end_header");
        const char* begin = file.data() + offset;
        const char* newline = static_cast<const char*>(std::memchr(begin, '\n', file.size() - offset));
        const char* end = newline ? newline : file.data() + file.size();
        offset = std::size_t(end - file.data()) + 1;
        if (offset > 65536) fail(n, "header longer than 64 KiB");
        const std::vector<std::string> words = splitWords(begin, end);
        const std::string keyword = words.empty() ? "" : words[0];
        if (keyword != "comment" && keyword != "obj_info")
            for (const char* p = begin; p < end; ++p)
                if ((static_cast<unsigned char>(*p) < 32 && !isBlank(*p)) || static_cast<unsigned char>(*p) > 126)
                    fail(n, "control or non-ASCII byte " + std::to_string(static_cast<unsigned char>(*p)));
        if (n == 1) {
            if (words.size() != 1 || keyword != "ply") fail(1, "expected 'ply'");
        } else if (keyword == "format") {
            if (formatSeen || words.size() != 3 || words[2] != "1.0" ||
                (words[1] != "ascii" && words[1] != "binary_little_endian" && words[1] != "binary_big_endian"))
                fail(n, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
            formatSeen = true;
            binary = words[1] != "ascii";
            bigEndian = words[1] == "binary_big_endian";
        } else if (keyword == "comment" || keyword == "obj_info") {
        } else if (keyword == "element") {
            Element e;
            if (words.size() != 3 || !isName(words[1]) || !parseCount(words[2], e.count))
                fail(n, "expected 'element NAME COUNT' (COUNT at most 2^32)");
            e.name = words[1];
            elements.push_back(e);
        } else if (keyword == "property") {
            const auto& types = scalarTypes();
            Property p;
            if (elements.empty()) fail(n, "property before any element");
            if (words.size() == 5 && words[1] == "list" && types.count(words[2]) && types.count(words[3]) &&
                isName(words[4]) && largestCount(types.at(words[2])) > 0) {
                p.isList = true;
                p.count = types.at(words[2]);
                p.value = types.at(words[3]);
            } else if (words.size() == 3 && types.count(words[1]) && isName(words[2])) {
                p.value = types.at(words[1]);
            } else {
                fail(n, "expected 'property TYPE NAME' or 'property list INTEGER_TYPE TYPE NAME'");
            }
            elements.back().properties.push_back(p);
        } else if (keyword == "end_header") {
            if (words.size() != 1) fail(n, "expected 'end_header' alone on its line");
            if (!formatSeen) fail(n, "no format line");
            return elements;
        } else {
            std::string shown = keyword.substr(0, 32);
            for (char& c : shown)
                if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
            fail(n, "unknown keyword '" + shown + "'");
        }
    }
}

std::uint64_t readUnsigned(const char* p, int bytes, bool bigEndian) {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t(static_cast<unsigned char>(p[bigEndian ? bytes - 1 - i : i])) << (8 * i);
    return v;
}

void walkBinary(const std::string& path, const MappedFile& file, const std::vector<Element>& elements, bool bigEndian,
                std::size_t offset) {
    for (const Element& e : elements) {
        for (std::uint64_t item = 0; item < e.count; ++item) {
            auto fail = [&](const std::string& why) {
                throw InputError(path + ": PLY element '" + e.name + "' item " + std::to_string(item) + ": " + why);
            };
            for (const Property& p : e.properties) {
                std::uint64_t bytes = std::uint64_t(p.value.bytes);
                if (p.isList) {
                    if (file.size() - offset < std::size_t(p.count.bytes)) fail("the file ends");
                    std::uint64_t count = readUnsigned(file.data() + offset, p.count.bytes, bigEndian);
                    if (p.count.isSigned && (count >> (8 * p.count.bytes - 1)) != 0) fail("negative list count");
                    offset += std::size_t(p.count.bytes);
                    if (count > (file.size() - offset) / bytes)
                        fail("list count " + std::to_string(count) + " runs past the end of the file");
                    bytes *= count;
                }
                if (file.size() - offset < bytes) fail("the file ends");
                offset += std::size_t(bytes);
            }
        }
    }
}

void walkAscii(const std::string& path, const MappedFile& file, const std::vector<Element>& elements,
               std::size_t offset) {
    for (const Element& e : elements) {
        for (std::uint64_t item = 0; item < e.count; ++item) {
            auto fail = [&](const std::string& why) {
                throw InputError(path + ": PLY element '" + e.name + "' item " + std::to_string(item) + ": " + why);
            };
            std::vector<std::string> words;
            while (words.empty()) {  // one item per line; blank lines between items are skipped
                if (offset >= file.size()) fail("the file ends");
                const char* begin = file.data() + offset;
                const char* newline = static_cast<const char*>(std::memchr(begin, '\n', file.size() - offset));
                const char* end = newline ? newline : file.data() + file.size();
                offset = std::size_t(end - file.data()) + 1;
                words = splitWords(begin, end);
            }
            std::size_t next = 0;
            for (const Property& p : e.properties) {
                std::uint64_t count = 1;
                if (p.isList) {
                    if (next >= words.size() || !parseCount(words[next], count) || count > largestCount(p.count))
                        fail("list count '" + words[std::min(next, words.size() - 1)].substr(0, 24) +
                             "' is not an integer its type holds");
                    ++next;
                }
                if (count > words.size() - next) fail("fewer values than its properties and list counts declare");
                for (std::uint64_t i = 0; i < count; ++i, ++next)
                    if (!isNumber(words[next])) fail("value '" + words[next].substr(0, 24) + "' is not a number");
            }
            if (next != words.size()) fail("more values than its properties declare");
        }
    }
}

}  // namespace

void checkPlyFile(const std::string& path) {
    const MappedFile file(path);
    bool binary = false, bigEndian = false;
    std::size_t offset = 0;
    const std::vector<Element> elements = readHeader(path, file, binary, bigEndian, offset);
    offset = std::min(offset, file.size());  // end_header may close the file without a newline
    // The cheapest bound first, with the clearest message: every element at its smallest
    // encoding (binary: its scalars and list counts; ASCII: two bytes per value).
    double minimumBytes = 0.0;
    for (const Element& e : elements)
        for (const Property& p : e.properties)
            minimumBytes += double(e.count) * (binary ? (p.isList ? p.count.bytes : p.value.bytes) : 2);
    const double available = double(file.size()) - double(offset);
    if (minimumBytes > available)
        throw InputError(path + ": PLY header declares elements of at least " + std::to_string((long long)minimumBytes) +
                         " bytes; the file holds " + std::to_string((long long)std::max(0.0, available)));
    if (binary) walkBinary(path, file, elements, bigEndian, offset);
    else walkAscii(path, file, elements, offset);
}

}  // namespace voxgi
