#include "x3d_prototypes.hpp"

#include "x3d_fields.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

namespace symcompress::x3d {
namespace {

constexpr int kMostNestedInstances = 32;                         // prototypes within prototypes
constexpr std::size_t kMostMadeElements = std::size_t(1) << 20;  // elements the expansion may copy in all

bool named(const pugi::xml_node& node, const char* name) { return std::strcmp(node.name(), name) == 0; }

// Whether `name` can be a field's name, and so an XML attribute's: a letter or _ first, then letters, digits, _.
bool isFieldName(const std::string& name) {
    auto letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
    return !name.empty() && letter(name[0]) && std::all_of(name.begin(), name.end(), [&](char c) {
        return letter(c) || std::isdigit(static_cast<unsigned char>(c));
    });
}

bool isDeclaration(const pugi::xml_node& node) {
    return named(node, "ProtoDeclare") || named(node, "ExternProtoDeclare");
}

// Calls `visit` on every element under `root` (itself too), depth first, without recursion; `visit` returns whether
// to look inside.
template <typename Visit>
void forEachElement(pugi::xml_node root, Visit visit) {
    std::vector<pugi::xml_node> stack{root};
    while (!stack.empty()) {
        const pugi::xml_node node = stack.back();
        stack.pop_back();
        if (node.type() != pugi::node_element || !visit(node)) continue;
        std::vector<pugi::xml_node> children;
        for (pugi::xml_node child : node.children()) children.push_back(child);
        stack.insert(stack.end(), children.rbegin(), children.rend());  // in document order
    }
}

std::size_t elementsIn(pugi::xml_node root) {
    std::size_t count = 0;
    forEachElement(root, [&](pugi::xml_node) { return ++count, true; });
    return count;
}

class Expander {
public:
    Expander(const std::filesystem::path& folder, const DocumentLoader& load) : folder_(folder), load_(load) {}

    PrototypeExpansion run(pugi::xml_node scene) {
        declare(scene);
        for (int level = 0; level < kMostNestedInstances; ++level) {
            std::vector<pugi::xml_node> instances = outermostInstances(scene);
            if (instances.empty()) break;
            for (pugi::xml_node instance : instances) expand(instance);
            if (level + 1 == kMostNestedInstances && !outermostInstances(scene).empty())
                out_.notes.insert("prototypes nested more than " + std::to_string(kMostNestedInstances) +
                                  " deep: the deeper ones not expanded");
        }
        return std::move(out_);
    }

private:
    // The ProtoDeclares under `root` by name, and the ExternProtoDeclares' from the files they name.
    void declare(pugi::xml_node root) {
        forEachElement(root, [&](pugi::xml_node node) {
            const std::string name = node.attribute("name").value();
            if (named(node, "ProtoDeclare")) declarations_.try_emplace(name, node);
            if (named(node, "ExternProtoDeclare") && !declarations_.count(name)) declareExternal(node, name);
            return true;  // a body may declare prototypes of its own
        });
    }

    void declareExternal(pugi::xml_node node, const std::string& name) {
        for (const std::string& url : parseStrings(node.attribute("url").value())) {
            if (url.find("://") != std::string::npos) continue;  // only local files
            const std::size_t hash = url.find('#');
            const std::filesystem::path file = folder_ / url.substr(0, hash);
            const std::string wanted = hash == std::string::npos ? "" : url.substr(hash + 1);
            auto [entry, added] = external_.try_emplace(file.lexically_normal().string());
            if (added) {
                entry->second = std::make_unique<pugi::xml_document>();
                if (!load_(file, *entry->second)) entry->second.reset();
            }
            if (!entry->second) continue;
            pugi::xml_node found;
            forEachElement(entry->second->document_element(), [&](pugi::xml_node candidate) {
                if (!found && named(candidate, "ProtoDeclare") &&
                    (wanted.empty() || wanted == candidate.attribute("name").value()))
                    found = candidate;
                return !found && !isDeclaration(candidate);
            });
            if (!found) continue;
            declarations_.try_emplace(name, found);
            if (added) declare(entry->second->document_element());  // the prototypes its body may use
            return;
        }
        out_.notes.insert("ExternProtoDeclare '" + name + "': no local file of its url declares it");
    }

    // The ProtoInstances under `root` not inside another one or a declaration, in document order.
    std::vector<pugi::xml_node> outermostInstances(pugi::xml_node root) const {
        std::vector<pugi::xml_node> found;
        forEachElement(root, [&](pugi::xml_node node) {
            if (named(node, "ProtoInstance") && !failed_.count(node.internal_object())) {
                found.push_back(node);
                return false;
            }
            return !isDeclaration(node);
        });
        return found;
    }

    void expand(pugi::xml_node instance) {
        pugi::xml_node parent = instance.parent();
        const std::string use = instance.attribute("USE").value(), name = instance.attribute("name").value();
        if (!use.empty()) {  // another use of an expanded instance: of its first node's type
            const auto type = typeOfDef_.find(use);
            if (type == typeOfDef_.end())
                return fail(instance, "ProtoInstance USE='" + use + "': no instance DEF'd so");
            pugi::xml_node reused = parent.insert_child_before(type->second.c_str(), instance);
            reused.append_attribute("USE") = use.c_str();
            keepContainerField(instance, reused);
            parent.remove_child(instance);
            return;
        }
        const auto declaration = declarations_.find(name);
        if (declaration == declarations_.end())
            return fail(instance, "ProtoInstance of '" + name + "': no prototype of that name declared");
        pugi::xml_node body = declaration->second.child("ProtoBody"), first;
        for (pugi::xml_node node : body.children())
            if (node.type() == pugi::node_element && !isDeclaration(node) && !named(node, "ROUTE")) {
                first = node;
                break;
            }
        ++out_.instances;
        if (!first) {  // a prototype that draws nothing
            parent.remove_child(instance);
            return;
        }
        pugi::xml_node copy = parent.insert_copy_before(first, instance);
        count(elementsIn(copy));
        connect(copy, fieldValues(declaration->second, instance));
        if (const pugi::xml_attribute def = instance.attribute("DEF")) {
            copy.remove_attribute("DEF");
            copy.append_attribute("DEF") = def.value();
            typeOfDef_[def.value()] = copy.name();
        }
        keepContainerField(instance, copy);
        parent.remove_child(instance);
    }

    // Each field's value, as the element that holds it (a `value` attribute, or nodes): the instance's
    // fieldValue, else the declaration's default.
    static std::map<std::string, pugi::xml_node> fieldValues(pugi::xml_node declaration, pugi::xml_node instance) {
        std::map<std::string, pugi::xml_node> values;
        for (pugi::xml_node field : declaration.child("ProtoInterface").children("field"))
            values[field.attribute("name").value()] = field;
        for (pugi::xml_node value : instance.children("fieldValue")) values[value.attribute("name").value()] = value;
        return values;
    }

    // Every IS connection in `copy` given its field's value: a node's field, or an inner instance's fieldValue.
    void connect(pugi::xml_node copy, const std::map<std::string, pugi::xml_node>& values) {
        std::vector<pugi::xml_node> connected;
        forEachElement(copy, [&](pugi::xml_node node) {
            if (node.child("IS")) connected.push_back(node);
            return !isDeclaration(node);
        });
        for (pugi::xml_node node : connected) {
            for (pugi::xml_node link : node.child("IS").children("connect")) {
                const std::string field = link.attribute("nodeField").value();
                const auto value = values.find(link.attribute("protoField").value());
                if (value == values.end()) continue;
                if (!isFieldName(field)) {
                    out_.notes.insert("an IS connect to the field '" + field + "', which is no field's name, left out");
                    continue;
                }
                const pugi::xml_attribute text = value->second.attribute("value");
                if (named(node, "ProtoInstance")) {
                    for (pugi::xml_node old = node.find_child_by_attribute("fieldValue", "name", field.c_str()); old;
                         old = node.find_child_by_attribute("fieldValue", "name", field.c_str()))
                        node.remove_child(old);
                    pugi::xml_node given = node.append_copy(value->second);
                    given.set_name("fieldValue");
                    for (const char* drop : {"type", "accessType"}) given.remove_attribute(drop);
                    given.attribute("name").set_value(field.c_str());
                    count(elementsIn(given));
                } else if (text) {
                    pugi::xml_attribute attribute = node.attribute(field.c_str());
                    if (!attribute) attribute = node.append_attribute(field.c_str());
                    attribute.set_value(text.value());
                } else {
                    for (pugi::xml_node child : value->second.children()) {
                        if (child.type() != pugi::node_element) continue;
                        pugi::xml_node given = node.append_copy(child);
                        if (!given.attribute("containerField"))
                            given.append_attribute("containerField") = field.c_str();
                        count(elementsIn(given));
                    }
                }
            }
            node.remove_child("IS");
        }
    }

    static void keepContainerField(pugi::xml_node from, pugi::xml_node to) {
        if (const pugi::xml_attribute field = from.attribute("containerField")) {
            to.remove_attribute("containerField");
            to.append_attribute("containerField") = field.value();
        }
    }

    void fail(pugi::xml_node instance, const std::string& note) {
        failed_.insert(instance.internal_object());
        out_.notes.insert(note);
    }

    void count(std::size_t elements) {
        made_ += elements;
        if (made_ > kMostMadeElements)
            throw std::length_error("prototype instances expand to more than " + std::to_string(kMostMadeElements) +
                                    " elements");
    }

    std::filesystem::path folder_;
    const DocumentLoader& load_;
    std::map<std::string, pugi::xml_node> declarations_;
    std::map<std::string, std::unique_ptr<pugi::xml_document>> external_;
    std::map<std::string, std::string> typeOfDef_;  // an expanded instance's DEF -> its first node's type
    std::set<const void*> failed_;
    std::size_t made_ = 0;
    PrototypeExpansion out_;
};

}  // namespace

PrototypeExpansion expandPrototypes(pugi::xml_node scene, const std::filesystem::path& folder,
                                    const DocumentLoader& load) {
    return Expander(folder, load).run(scene);
}

}  // namespace symcompress::x3d
