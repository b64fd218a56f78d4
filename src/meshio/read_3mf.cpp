#include "meshio/read_3mf.h"

#include <array>
#include <cstdint>
#include <map>
#include <string_view>
#include <vector>

#include "io/xml_scanner.h"
#include "io/zip_archive.h"
#include "meshio/load_mesh.h"
#include "meshio/read_text.h"

namespace offsetopt {

namespace {

constexpr int kMaxComponentDepth = 32;
constexpr std::size_t kMaxParts = 4096;
// Components form a DAG that can name one object exponentially often with no vertices in it.
constexpr std::int64_t kMaxInstances = std::int64_t{1} << 20;
// And the build may place at most this many times the vertices the parts store (plus a slack for
// small files), so memory stays proportional to the inflated input, as for the other readers.
constexpr std::int64_t kMaxRepeat = 64;
constexpr std::int64_t kRepeatSlack = std::int64_t{1} << 16;
const char* const kModelRelationship = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";

// A 3MF transform "m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32": points are row vectors,
// p' = [x y z 1] * M (3MF Core 1.3, 3.3).
using Transform = std::array<double, 12>;
constexpr Transform kIdentity = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};

// `first` applied, then `then`.
Transform compose(const Transform& first, const Transform& then) {
  Transform c{};
  for (int r = 0; r < 4; ++r)
    for (int col = 0; col < 3; ++col) {
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) sum += first[3 * r + k] * then[3 * k + col];
      c[3 * r + col] = sum + (r == 3 ? then[9 + col] : 0.0);
    }
  return c;
}

double determinant(const Transform& m) {
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
}

struct Component {
  std::string part;  // empty: the part the component is in
  std::int64_t object = 0;
  Transform transform = kIdentity;
  int line = 0;
};

struct Object {
  int line = 0;
  std::string type = "model";
  bool has_mesh = false;
  std::vector<double> xyz;
  std::vector<int> corners;
  std::vector<Component> components;
};

struct Part {
  std::string unit = "millimeter";
  std::map<std::int64_t, Object> objects;
  std::vector<Component> items;  // the build
};

bool lower_equal(std::string_view a, std::string_view b) { return equals_ignoring_case(a, b); }

class Reader {
 public:
  Reader(const std::string& name, const std::string& bytes)
      : name_(name), archive_(bytes), builder_(name, MeshFormat::three_mf, false) {}

  RawMesh read() {
    std::string error;
    if (!list_zip(archive_, entries_, error)) throw MeshInputError(name_ + ": " + error);
    const std::string root = root_part();
    const Part& part = load(root);
    if (part.unit != "millimeter")
      builder_.warnings().push_back("3MF unit is " + part.unit + "; coordinates are kept in " + part.unit +
                                    " (3MF outputs keep this unit unless --unit says otherwise)");
    if (part.items.empty()) throw MeshInputError(name_ + ": " + quote_bytes(root) + ": no <item> in <build>: nothing to print");
    for (const Component& item : part.items) emit(root, item, kIdentity, 0, root);
    if (skipped_ > 0)
      builder_.warnings().push_back(std::to_string(skipped_) + " build item(s) or component(s) of type support, solidsupport, surface or other left out");
    RawMesh raw = builder_.finish();
    raw.unit = part.unit;
    return raw;
  }

 private:
  [[noreturn]] void refuse(const std::string& part, int line, const std::string& what) const {
    throw MeshInputError(name_ + ": " + quote_bytes(part) + (line > 0 ? ": line " + std::to_string(line) : std::string()) + ": " + what);
  }

  const ZipEntryInfo* find(std::string_view part_name) const {
    for (const ZipEntryInfo& e : entries_)
      if (lower_equal(e.name, part_name)) return &e;
    return nullptr;
  }

  std::string extract(const ZipEntryInfo& entry) {
    std::string out, error;
    const std::uint64_t left = kMaxFileBytes - inflated_;
    if (!extract_zip_entry(archive_, entry, static_cast<std::size_t>(left), out, error)) {
      if (entry.size > left)
        throw MeshInputError(name_ + ": the package's parts inflate to more than " + std::to_string(kMaxFileBytes) +
                             " bytes (the supported maximum)");
      throw MeshInputError(name_ + ": " + error);
    }
    inflated_ += out.size();
    return out;
  }

  static std::string part_name(std::string_view target) {
    while (!target.empty() && target[0] == '/') target.remove_prefix(1);
    return std::string(target);
  }

  // The model part the package relationship names (OPC, 3MF Core 1.3, 2.1.1).
  std::string root_part() {
    const ZipEntryInfo* rels = find("_rels/.rels");
    if (rels) {
      const std::string text = extract(*rels);
      XmlScanner x(text);
      std::string target;
      for (;;) {
        if (!x.next()) refuse("_rels/.rels", 0, x.error());
        if (x.kind() == XmlTokenKind::eof) break;
        if (x.kind() != XmlTokenKind::start || x.local_name() != "Relationship") continue;
        const std::string* type = x.attribute("Type");
        const std::string* t = x.attribute("Target");
        if (type && t && *type == kModelRelationship && target.empty()) target = part_name(*t);
      }
      if (!target.empty()) {
        if (!find(target)) refuse("_rels/.rels", 0, "the model part '" + quote_bytes(target) + "' is not in the package");
        return target;
      }
    }
    if (find("3D/3dmodel.model")) return "3D/3dmodel.model";
    throw MeshInputError(name_ + ": no 3D model part (neither a 3dmodel relationship in _rels/.rels nor 3D/3dmodel.model)");
  }

  const Part& load(const std::string& key) {
    std::string lowered = key;
    for (char& c : lowered)
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    auto found = parts_.find(lowered);
    if (found != parts_.end()) return found->second;
    if (parts_.size() >= kMaxParts) refuse(key, 0, "more than " + std::to_string(kMaxParts) + " model parts");
    const ZipEntryInfo* entry = find(key);
    if (!entry) throw MeshInputError(name_ + ": model part '" + quote_bytes(key) + "' is not in the package");
    const std::string text = extract(*entry);
    Part part = parse(key, text);
    for (const auto& entry_object : part.objects) stored_vertices_ += static_cast<std::int64_t>(entry_object.second.xyz.size() / 3);
    return parts_.emplace(lowered, std::move(part)).first->second;
  }

  Transform parse_transform(const std::string& part, int line, const std::string& text) {
    std::vector<std::string_view> tokens;
    split_tokens(text, tokens, true);
    Transform m{};
    if (tokens.size() != 12) refuse(part, line, "transform needs 12 numbers, got " + std::to_string(tokens.size()));
    for (int i = 0; i < 12; ++i)
      if (!parse_real(tokens[i], m[i]) || !(m[i] - m[i] == 0.0))
        refuse(part, line, "transform value '" + quote_bytes(tokens[i]) + "' is not a finite number");
    return m;
  }

  std::int64_t parse_id(const std::string& part, int line, const std::string* text, const char* what) {
    if (!text) refuse(part, line, std::string("missing attribute ") + what);
    std::int64_t value = 0;
    bool overflow = false;
    if (!parse_integer(*text, value, overflow) || overflow || value < 0 || value > 0x7FFFFFFF)
      refuse(part, line, std::string(what) + " '" + quote_bytes(*text) + "' is not an index in [0, 2^31)");
    return value;
  }

  // The optional p:path of a component or item: the part its object lives in.
  static std::string path_attribute(const XmlScanner& x) {
    for (const char* qualified : {"p:path", "path"})
      if (const std::string* p = x.attribute(qualified)) return part_name(*p);
    return std::string();
  }

  Part parse(const std::string& key, const std::string& text) {
    Part part;
    XmlScanner x(text);
    std::vector<std::string_view> path;  // local names of the open elements
    Object* object = nullptr;
    std::int64_t object_id = -1;
    std::int64_t vertices = 0, triangles = 0;
    const auto under = [&](std::initializer_list<const char*> names) {
      if (path.size() != names.size()) return false;
      std::size_t i = 0;
      for (const char* n : names)
        if (path[i++] != n) return false;
      return true;
    };
    for (;;) {
      if (!x.next()) refuse(key, 0, x.error());
      if (x.kind() == XmlTokenKind::eof) break;
      const int line = x.line();
      if (x.kind() == XmlTokenKind::end) {
        if (object && path.size() == 3 && path[2] == "object") {
          const std::int64_t nv = static_cast<std::int64_t>(object->xyz.size() / 3);
          for (std::size_t t = 0; t < object->corners.size(); ++t)
            if (object->corners[t] >= nv)
              refuse(key, object->line, "object " + std::to_string(object_id) + ": triangle " + std::to_string(t / 3) +
                                            " uses vertex " + std::to_string(object->corners[t]) + ", but the object has " +
                                            std::to_string(nv) + " vertices");
          object = nullptr;
        }
        path.pop_back();
        continue;
      }
      path.push_back(x.local_name());
      if (path.size() == 1) {
        if (path[0] != "model") refuse(key, line, "the root element is <" + quote_bytes(x.name()) + ">, not <model>");
        if (const std::string* unit = x.attribute("unit")) {
          static const char* const kUnits[] = {"micron", "millimeter", "centimeter", "inch", "foot", "meter"};
          bool known = false;
          for (const char* u : kUnits) known = known || *unit == u;
          if (!known) refuse(key, line, "unknown unit '" + quote_bytes(*unit) + "'");
          part.unit = *unit;
        }
      } else if (under({"model", "resources", "object"})) {
        object_id = parse_id(key, line, x.attribute("id"), "id");
        auto [it, inserted] = part.objects.emplace(object_id, Object{});
        if (!inserted) refuse(key, line, "a second object with id " + std::to_string(object_id));
        object = &it->second;
        object->line = line;
        if (const std::string* type = x.attribute("type")) object->type = *type;
      } else if (object && under({"model", "resources", "object", "mesh"})) {
        object->has_mesh = true;
      } else if (object && under({"model", "resources", "object", "mesh", "vertices", "vertex"})) {
        if (++vertices > kMaxVertices)
          refuse(key, line, "more than " + std::to_string(kMaxVertices) + " vertices (the supported maximum)");
        for (const char* axis : {"x", "y", "z"}) {
          const std::string* value = x.attribute(axis);
          if (!value) refuse(key, line, std::string("vertex without attribute ") + axis);
          double v = 0.0;
          if (!parse_real(*value, v)) refuse(key, line, std::string("vertex ") + axis + " '" + quote_bytes(*value) + "' is not a number");
          object->xyz.push_back(v);
        }
      } else if (object && under({"model", "resources", "object", "mesh", "triangles", "triangle"})) {
        if (++triangles > kMaxFaces)
          refuse(key, line, "more than " + std::to_string(kMaxFaces) + " triangles (the supported maximum)");
        for (const char* corner : {"v1", "v2", "v3"})
          object->corners.push_back(static_cast<int>(parse_id(key, line, x.attribute(corner), corner)));
      } else if (object && under({"model", "resources", "object", "components", "component"})) {
        if (object->components.size() >= static_cast<std::size_t>(kMaxFaces)) refuse(key, line, "too many components");
        Component c;
        c.line = line;
        c.object = parse_id(key, line, x.attribute("objectid"), "objectid");
        if (const std::string* t = x.attribute("transform")) c.transform = parse_transform(key, line, *t);
        c.part = path_attribute(x);
        object->components.push_back(std::move(c));
      } else if (under({"model", "build", "item"})) {
        if (part.items.size() >= static_cast<std::size_t>(kMaxFaces)) refuse(key, line, "too many build items");
        Component c;
        c.line = line;
        c.object = parse_id(key, line, x.attribute("objectid"), "objectid");
        if (const std::string* t = x.attribute("transform")) c.transform = parse_transform(key, line, *t);
        c.part = path_attribute(x);
        part.items.push_back(std::move(c));
      }
    }
    return part;
  }

  // Adds the object `ref` names (in `ref.part`, or `current`) with `ref.transform` then `outer`.
  void emit(const std::string& current, const Component& ref, const Transform& outer, int depth, const std::string& from) {
    if (++instances_ > kMaxInstances)
      refuse(from, ref.line, "more than " + std::to_string(kMaxInstances) + " object instances in the build");
    if (depth >= kMaxComponentDepth)
      refuse(from, ref.line, "components nested deeper than " + std::to_string(kMaxComponentDepth) + " (or a reference cycle)");
    const std::string key = ref.part.empty() ? current : ref.part;
    const Part& part = load(key);
    const auto found = part.objects.find(ref.object);
    if (found == part.objects.end())
      refuse(from, ref.line, "object " + std::to_string(ref.object) + " is not defined in " + quote_bytes(key));
    const Object& object = found->second;
    if (object.type != "model") {
      ++skipped_;
      return;
    }
    const std::int64_t count = static_cast<std::int64_t>(object.xyz.size() / 3);
    if (builder_.vertex_count() + count > kMaxRepeat * stored_vertices_ + kRepeatSlack)
      refuse(from, ref.line, "the build repeats its objects to more than " + std::to_string(kMaxRepeat) +
                                 " times the vertices the file stores (" + std::to_string(stored_vertices_) + ")");
    const Transform m = compose(ref.transform, outer);
    const bool identity = m == kIdentity;
    const std::int64_t base = builder_.vertex_count();
    for (std::size_t i = 0; i + 2 < object.xyz.size(); i += 3) {
      const double px = object.xyz[i], py = object.xyz[i + 1], pz = object.xyz[i + 2];
      if (identity) {
        builder_.add_vertex(px, py, pz);
      } else {
        builder_.add_vertex(px * m[0] + py * m[3] + pz * m[6] + m[9], px * m[1] + py * m[4] + pz * m[7] + m[10],
                            px * m[2] + py * m[5] + pz * m[8] + m[11]);
      }
    }
    const bool mirrored = determinant(m) < 0.0;
    for (std::size_t t = 0; t + 2 < object.corners.size(); t += 3) {
      int c[3] = {static_cast<int>(base + object.corners[t]), static_cast<int>(base + object.corners[t + 1]),
                  static_cast<int>(base + object.corners[t + 2])};
      if (mirrored) std::swap(c[1], c[2]);
      builder_.add_polygon(c, 3);
    }
    for (const Component& child : object.components) emit(key, child, m, depth + 1, key);
  }

  const std::string& name_;
  std::string_view archive_;
  std::vector<ZipEntryInfo> entries_;
  std::map<std::string, Part> parts_;
  std::uint64_t inflated_ = 0;
  RawMeshBuilder builder_;
  std::int64_t skipped_ = 0;
  std::int64_t instances_ = 0;
  std::int64_t stored_vertices_ = 0;
};

}  // namespace

bool looks_like_zip(const std::string& bytes) { return bytes.size() >= 4 && bytes.compare(0, 4, "PK\x03\x04", 4) == 0; }

RawMesh read_3mf(const std::string& name, const std::string& bytes) { return Reader(name, bytes).read(); }

}  // namespace offsetopt
