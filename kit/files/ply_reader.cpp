#include "files/ply_reader.h"

#include "files/values.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace pcl_ncut_seg {
namespace files {

namespace {

constexpr std::size_t kMaxHeaderBytes = 1 << 20;

struct Property {
  std::string name;
  std::uint8_t type = 0;       ///< of the value (of a list: of each item)
  std::uint8_t count_type = 0; ///< of a list's count; 0 for a scalar
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Format { Ascii, Little, Big };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::uint64_t data_offset = 0;
  std::size_t data_line = 0; ///< 1-based, of the first data line (ascii)
};

std::uint8_t plyType(const std::string& t) {
  using F = pcl::PCLPointField;
  if (t == "char" || t == "int8")
    return F::INT8;
  if (t == "uchar" || t == "uint8")
    return F::UINT8;
  if (t == "short" || t == "int16")
    return F::INT16;
  if (t == "ushort" || t == "uint16")
    return F::UINT16;
  if (t == "int" || t == "int32")
    return F::INT32;
  if (t == "uint" || t == "uint32")
    return F::UINT32;
  if (t == "float" || t == "float32")
    return F::FLOAT32;
  if (t == "double" || t == "float64")
    return F::FLOAT64;
  return 0;
}

bool isInteger(std::uint8_t type) {
  return type != pcl::PCLPointField::FLOAT32 && type != pcl::PCLPointField::FLOAT64;
}

bool isFaceList(const Property& p) {
  return p.count_type != 0 && (p.name == "vertex_indices" || p.name == "vertex_index");
}

/** One header line into h; false with the reason. */
bool headerLine(const std::vector<std::string>& w, Header& h, bool& has_format,
                std::string& error) {
  if (w[0] == "comment" || w[0] == "obj_info")
    return true;
  if (w[0] == "format" && w.size() == 3 && !has_format) {
    has_format = true;
    h.format = w[1] == "ascii"                  ? Format::Ascii
               : w[1] == "binary_little_endian" ? Format::Little
                                                : Format::Big;
    if (w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian")
      return true;
  }
  std::uint64_t count = 0;
  if (w[0] == "element" && w.size() == 3 && parseCount(w[2], count)) {
    h.elements.push_back({w[1], count, {}});
    return true;
  }
  if (w[0] == "property" && !h.elements.empty()) {
    Property p;
    if (w.size() == 3)
      p = {w[2], plyType(w[1]), 0};
    else if (w.size() == 5 && w[1] == "list")
      p = {w[4], plyType(w[3]), plyType(w[2])};
    if (p.type != 0 && (w.size() == 3 || (p.count_type != 0 && isInteger(p.count_type)))) {
      if (isFaceList(p) && !isInteger(p.type)) {
        error = "list '" + p.name + "' of " + w[3] + " values: vertex indices are integers";
        return false;
      }
      h.elements.back().properties.push_back(p);
      return true;
    }
  }
  error = "not a PLY header line";
  return false;
}

bool readHeader(const FileBytes& file, Header& h, std::string& error) {
  std::string text;
  if (!file.readRest(0, text, error, kMaxHeaderBytes))
    return false;
  TextLine line;
  if (!nextLine(text, 0, line) || text.compare(line.begin, line.end - line.begin, "ply") != 0) {
    error = "it does not start with 'ply'";
    return false;
  }
  bool has_format = false;
  std::size_t number = 1;
  for (std::size_t pos = line.next; nextLine(text, pos, line); pos = line.next) {
    ++number;
    const std::vector<std::string> w = words(text.data() + line.begin, text.data() + line.end);
    if (w.empty())
      continue;
    if (w[0] == "end_header" && w.size() == 1) {
      if (!has_format) {
        error = "no format line";
        return false;
      }
      h.data_offset = line.next;
      h.data_line = number + 1;
      return true;
    }
    if (!headerLine(w, h, has_format, error)) {
      error = "line " + std::to_string(number) + ": " +
              quoted(text.data() + line.begin, text.data() + line.end) + ": " + error;
      return false;
    }
  }
  error = "the header ends without end_header";
  return false;
}

/** The values of the data, record by record: an ascii line each, or packed binary. */
class Body {
public:
  Body(const FileBytes& file, const Header& h, std::string& error) : h_(h), error_(error) {
    if (file.readRest(h.data_offset, data_, error))
      ok_ = true;
    line_number_ = h.data_line - 1; // begin() counts each record's line
  }
  bool ok() const { return ok_; }
  std::uint64_t remaining() const { return data_.size() - pos_; }
  /** The most values of the type a list of the record can still hold. */
  std::uint64_t listBound(std::uint8_t type) const {
    if (h_.format == Format::Ascii)
      return static_cast<std::uint64_t>(end_ - p_ + 1) / 2; // a digit and a separator each
    return remaining() / typeSize(type);
  }

  /** Start a record of element e (number i); ascii: its line. */
  bool begin(const Element& e, std::uint64_t i) {
    element_ = &e;
    record_ = i;
    if (h_.format != Format::Ascii)
      return true;
    TextLine line;
    if (!nextLine(data_, pos_, line))
      return fail("the data ends");
    p_ = data_.data() + line.begin;
    end_ = data_.data() + line.end;
    pos_ = line.next;
    ++line_number_;
    return true;
  }
  /** One value of the type into out (native order). */
  bool value(std::uint8_t type, void* out) {
    const std::size_t size = typeSize(type);
    if (h_.format != Format::Ascii) {
      if (remaining() < size)
        return fail("the data ends");
      auto* o = static_cast<char*>(out);
      std::memcpy(o, data_.data() + pos_, size);
      if (h_.format == Format::Big)
        std::reverse(o, o + size);
      pos_ += size;
      return true;
    }
    while (p_ != end_ && isBlank(*p_))
      ++p_;
    const char* token = p_;
    while (p_ != end_ && !isBlank(*p_))
      ++p_;
    if (token == p_)
      return fail("a value is missing");
    if (!parseValue(token, p_, type, out))
      return fail(quoted(token, p_) + " is not a value of its type");
    return true;
  }
  /** An integer value (a list's count, a vertex index). */
  bool integer(std::uint8_t type, std::int64_t& out) {
    std::uint8_t bytes[8] = {};
    if (!value(type, bytes))
      return false;
    out = integerValue(bytes, type);
    return true;
  }
  /** End the record; ascii: nothing more on its line. */
  bool end() {
    if (h_.format != Format::Ascii)
      return true;
    while (p_ != end_ && isBlank(*p_))
      ++p_;
    return p_ == end_ || fail("more values than the element's properties");
  }
  /** After the last element: ascii allows only white space. */
  bool finish() {
    if (h_.format == Format::Ascii)
      for (; pos_ < data_.size(); ++pos_)
        if (!isBlank(data_[pos_]) && data_[pos_] != '\n') {
          ++line_number_;
          element_ = nullptr;
          return fail("data after the last element");
        }
    return true;
  }
  bool fail(const std::string& what) {
    error_ = (h_.format == Format::Ascii ? "line " + std::to_string(line_number_) + ": " : "") +
             (element_ ? "element '" + element_->name + "' record " + std::to_string(record_) + ": "
                       : "") +
             what;
    return false;
  }

private:
  const Header& h_;
  std::string& error_;
  std::string data_;
  std::size_t pos_ = 0;
  const char *p_ = nullptr, *end_ = nullptr;
  std::size_t line_number_ = 0;
  const Element* element_ = nullptr;
  std::uint64_t record_ = 0;
  bool ok_ = false;
};

/** The smallest bytes (binary) or characters (ascii) a record of e can take. */
std::uint64_t minimumRecord(const Element& e, Format format) {
  std::uint64_t bytes = 0;
  for (const Property& p : e.properties)
    bytes += format == Format::Ascii ? 2 : typeSize(p.count_type ? p.count_type : p.type);
  return bytes;
}

/** The vertex element's scalar properties as PCL fields. */
void vertexFields(const Element& e, pcl::PCLPointCloud2& blob) {
  std::uint32_t offset = 0;
  for (const Property& p : e.properties)
    if (p.count_type == 0) {
      pcl::PCLPointField f;
      f.name = p.name;
      f.offset = offset;
      f.datatype = p.type;
      f.count = 1;
      blob.fields.push_back(f);
      offset += static_cast<std::uint32_t>(typeSize(p.type));
    }
  blob.point_step = offset;
}

/** Every record of element e: a vertex's scalars into the blob, a face's vertex list into
 * ply, everything else read and dropped. */
bool readElement(Body& body, const Element& e, bool vertex, bool face, PlyContents& ply) {
  std::uint8_t scratch[8];
  pcl::PCLPointCloud2& blob = ply.vertices;
  for (std::uint64_t i = 0; i < e.count; ++i) {
    if (!body.begin(e, i))
      return false;
    std::uint8_t* out = vertex ? blob.data.data() + i * blob.point_step : nullptr;
    for (const Property& p : e.properties) {
      if (p.count_type == 0) {
        if (!body.value(p.type, out ? out : scratch))
          return false;
        if (out)
          out += typeSize(p.type);
        continue;
      }
      std::int64_t n = 0;
      if (!body.integer(p.count_type, n))
        return false;
      if (n < 0 || static_cast<std::uint64_t>(n) > body.listBound(p.type))
        return body.fail("a list of " + std::to_string(n) + " values cannot be read");
      const bool keep = face && isFaceList(p);
      for (std::int64_t k = 0; k < n; ++k) {
        std::int64_t index = 0;
        if (!(keep ? body.integer(p.type, index) : body.value(p.type, scratch)))
          return false;
        if (keep)
          ply.face_indices.push_back(index);
      }
      if (keep)
        ply.face_offsets.push_back(ply.face_indices.size());
    }
    if (!body.end())
      return false;
  }
  return true;
}

} // namespace

bool readPly(const FileBytes& file, PlyContents& ply, std::string& error) {
  ply = PlyContents();
  Header h;
  if (!readHeader(file, h, error))
    return false;
  Body body(file, h, error);
  if (!body.ok())
    return false;
  bool seen_vertex = false;
  for (const Element& e : h.elements) {
    const bool vertex = e.name == "vertex";
    const bool face =
        e.name == "face" && std::any_of(e.properties.begin(), e.properties.end(), isFaceList);
    if ((vertex && seen_vertex) || (face && ply.has_faces)) {
      error = "a second '" + e.name + "' element";
      return false;
    }
    const std::uint64_t least = minimumRecord(e, h.format);
    if (e.count > 0 && (least == 0 || e.count > body.remaining() / least)) {
      error = "element '" + e.name + "' of " + std::to_string(e.count) + " records" +
              (least == 0 ? " has no properties" : " cannot fit in the data left");
      return false;
    }
    if (vertex && e.count > std::numeric_limits<std::uint32_t>::max()) {
      error = "more than 2^32 vertices";
      return false;
    }
    if (vertex) {
      seen_vertex = true;
      vertexFields(e, ply.vertices);
      ply.vertices.width = static_cast<std::uint32_t>(e.count);
      ply.vertices.height = 1;
      ply.vertices.row_step = ply.vertices.point_step * ply.vertices.width;
      ply.vertices.data.assign(static_cast<std::size_t>(e.count) * ply.vertices.point_step, 0);
    }
    if (face) {
      ply.has_faces = true;
      ply.face_offsets.assign(1, 0);
      ply.face_offsets.reserve(static_cast<std::size_t>(e.count) + 1);
    }
    if (!readElement(body, e, vertex, face, ply))
      return false;
  }
  if (!seen_vertex) {
    error = "no vertex element";
    return false;
  }
  return body.finish();
}

} // namespace files
} // namespace pcl_ncut_seg
