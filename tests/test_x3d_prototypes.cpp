// X3D prototypes (ProtoDeclare, ExternProtoDeclare, ProtoInstance) are expanded as a browser expands them, so that
// what they draw comes out (issue 15: never lossier): field values by value and by node, defaults, nested
// prototypes, DEF and USE of instances; what cannot be expanded is said, and no file expands without bound.
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <set>

using namespace symcompress;
using namespace symcompress::testing;
namespace fs = std::filesystem;

namespace {

// A pillar: a cylinder of the given height and colour, and on top (1.2 above) the node of its `top` field.
const std::string kPillar = R"(<ProtoDeclare name='Pillar'>
 <ProtoInterface>
  <field name='height' type='SFFloat' accessType='initializeOnly' value='2'/>
  <field name='color' type='SFColor' accessType='inputOutput' value='0.8 0.2 0.2'/>
  <field name='top' type='SFNode' accessType='initializeOnly'><Sphere radius='0.4'/></field>
 </ProtoInterface>
 <ProtoBody>
  <Group>
   <Shape><Appearance><Material DEF='paint'><IS><connect nodeField='diffuseColor' protoField='color'/></IS></Material>
    </Appearance><Cylinder radius='0.3'><IS><connect nodeField='height' protoField='height'/></IS></Cylinder></Shape>
   <Transform translation='0 1.2 0'><Shape><Appearance><Material USE='paint'/></Appearance>
    <IS><connect nodeField='geometry' protoField='top'/></IS></Shape></Transform>
  </Group>
  <ROUTE fromNode='paint' fromField='diffuseColor' toNode='paint' toField='diffuseColor'/>
 </ProtoBody>
</ProtoDeclare>)";

std::string sceneX3d(const std::string& content) {
    return "<X3D profile='Immersive' version='3.3'><Scene>" + content + "</Scene></X3D>";
}

std::string joinedWarnings(const Scene& scene) {
    std::string out;
    for (const std::string& warning : scene.warnings) out += warning + "\n";
    return out;
}

// The world's triangles of each mesh a node draws, by the y of their boxes' bottom and top (rounded to 1e-6).
std::multiset<std::pair<double, double>> drawnHeights(const Scene& scene) {
    std::multiset<std::pair<double, double>> out;
    const std::vector<Eigen::Matrix4d> world = worldTransforms(scene);
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        if (scene.nodes[n].mesh < 0) continue;
        for (const Primitive& primitive : scene.meshes[std::size_t(scene.nodes[n].mesh)].primitives) {
            double low = HUGE_VAL, high = -HUGE_VAL;
            for (const Eigen::Vector3d& p : primitive.positions) {
                const double y = (world[n] * p.homogeneous()).y();
                low = std::min(low, y), high = std::max(high, y);
            }
            out.insert({std::round(low * 1e6) / 1e6, std::round(high * 1e6) / 1e6});
        }
    }
    return out;
}

}  // namespace

TEST_CASE("A ProtoInstance draws its prototype's first node, its fields given by value, by node or by default",
          "[io][x3d][prototypes]") {
    TemporaryFolder folder;
    SECTION("defaults, values and a node in place of the default one") {
        writeTextFile(folder / "pillars.x3d",
                      sceneX3d(kPillar + "<ProtoInstance name='Pillar'/>"
                                         "<Transform translation='3 0 0'><ProtoInstance name='Pillar'>"
                                         "<fieldValue name='height' value='4'/><fieldValue name='color' value='0 0 1'/>"
                                         "<fieldValue name='top'><Box size='0.5 0.5 0.5'/></fieldValue>"
                                         "</ProtoInstance></Transform>"));
        const Scene scene = readScene(folder / "pillars.x3d");
        INFO(joinedWarnings(scene));
        // Cylinders from -h/2 to h/2; the top node 1.2 above the origin: a sphere of radius 0.4, a box of 0.5.
        CHECK(drawnHeights(scene) ==
              std::multiset<std::pair<double, double>>{{-1, 1}, {0.8, 1.6}, {-2, 2}, {0.95, 1.45}});
        // Two materials: the default red and the given blue, each shared by its pillar's two shapes.
        std::set<std::vector<double>> colors;
        for (const Mesh& mesh : scene.meshes)
            for (const Primitive& primitive : mesh.primitives) {
                const Eigen::Vector4d& c = scene.materials[std::size_t(primitive.material)].baseColorFactor;
                colors.insert({c.x(), c.y(), c.z()});
            }
        CHECK(colors.size() == 2);
        CHECK(colors.count({0, 0, 1}) == 1);
        CHECK(joinedWarnings(scene).find("ProtoInstance") == std::string::npos);
    }
    SECTION("a prototype whose body instances another, its field passed on through IS; an instance DEF'd and USEd") {
        writeTextFile(
            folder / "rows.x3d",
            sceneX3d(kPillar + "<ProtoDeclare name='Pair'><ProtoInterface><field name='h' type='SFFloat' "
                               "accessType='initializeOnly' value='1'/></ProtoInterface><ProtoBody><Group>"
                               "<ProtoInstance name='Pillar'><IS><connect nodeField='height' protoField='h'/></IS>"
                               "</ProtoInstance><Transform translation='2 0 0'><ProtoInstance name='Pillar'>"
                               "<fieldValue name='height' value='6'/></ProtoInstance></Transform></Group></ProtoBody>"
                               "</ProtoDeclare>"
                               "<Transform><ProtoInstance name='Pair' DEF='pair'><fieldValue name='h' value='3'/>"
                               "</ProtoInstance></Transform>"
                               "<Transform translation='0 0 5'><ProtoInstance name='Pair' USE='pair'/></Transform>"));
        const Scene scene = readScene(folder / "rows.x3d");
        INFO(joinedWarnings(scene));
        // Each pair: a pillar of height 3 (the instance's h), one of 6; drawn twice, by the DEF and the USE.
        CHECK(drawnHeights(scene) ==
              std::multiset<std::pair<double, double>>{
                  {-1.5, 1.5}, {-1.5, 1.5}, {-3, 3}, {-3, 3}, {0.8, 1.6}, {0.8, 1.6}, {0.8, 1.6}, {0.8, 1.6}});
    }
    SECTION("an ExternProtoDeclare whose url names a local file") {
        writeTextFile(folder / "library.x3d", sceneX3d(kPillar));
        writeTextFile(folder / "uses.x3d",
                      sceneX3d("<ExternProtoDeclare name='Column' url='\"http://example.com/x.x3d#Pillar\" "
                               "\"library.x3d#Pillar\"'><field name='height' type='SFFloat' "
                               "accessType='initializeOnly'/></ExternProtoDeclare>"
                               "<Transform><ProtoInstance name='Column'><fieldValue name='height' value='8'/>"
                               "</ProtoInstance></Transform>"));
        const Scene scene = readScene(folder / "uses.x3d");
        INFO(joinedWarnings(scene));
        CHECK(drawnHeights(scene) == std::multiset<std::pair<double, double>>{{-4, 4}, {0.8, 1.6}});
    }
}

TEST_CASE("Prototypes that cannot be expanded are said, and none expands without bound", "[io][x3d][prototypes]") {
    TemporaryFolder folder;
    SECTION("an unknown prototype, an external one without a file: warnings naming them, the rest read") {
        writeTextFile(
            folder / "missing.x3d",
            sceneX3d(kPillar + "<ExternProtoDeclare name='Far' url='\"nowhere.x3d#Far\"'/>"
                               "<Transform><ProtoInstance name='Pillar'/></Transform><ProtoInstance name='Ghost'/>"
                               "<ProtoInstance name='Far'/>"));
        const Scene scene = readScene(folder / "missing.x3d");
        const std::string warnings = joinedWarnings(scene);
        CHECK_THAT(warnings,
                   Catch::Contains("missing.x3d: ProtoInstance of 'Ghost': no prototype of that name declared"));
        CHECK_THAT(warnings,
                   Catch::Contains("missing.x3d: ExternProtoDeclare 'Far': no local file of its url declares it"));
        CHECK(drawnHeights(scene).size() == 2);
    }
    SECTION("a prototype that instances itself stops at 32 levels, with a warning") {
        writeTextFile(folder / "self.x3d",
                      sceneX3d("<ProtoDeclare name='Tower'><ProtoBody><Transform translation='0 1 0'><Shape><Box/>"
                               "</Shape><ProtoInstance name='Tower'/></Transform></ProtoBody></ProtoDeclare>"
                               "<ProtoInstance name='Tower'/>"));
        const Scene scene = readScene(folder / "self.x3d");
        CHECK(drawnHeights(scene).size() == 32);
        CHECK_THAT(joinedWarnings(scene), Catch::Contains("nested more than 32 deep"));
    }
    SECTION("one that doubles at every level: a clear error, not all memory") {
        writeTextFile(folder / "double.x3d",
                      sceneX3d("<ProtoDeclare name='Twice'><ProtoBody><Group><Shape><Box/></Shape>"
                               "<ProtoInstance name='Twice'/><ProtoInstance name='Twice'/></Group></ProtoBody>"
                               "</ProtoDeclare><ProtoInstance name='Twice'/>"));
        CHECK_THROWS_WITH(readScene(folder / "double.x3d"),
                          Catch::Contains("double.x3d") && Catch::Contains("prototype instances expand to more than"));
    }
}

TEST_CASE("Prototype instances render in X3D output as the input does in X_ITE", "[io][x3d][prototypes][renders]") {
    if (!renderAvailable()) {
        WARN("skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    TemporaryFolder folder;
    // Each instance under a Transform: render_compare.sh lists the shapes of X_ITE's root nodes, which a root
    // ProtoInstance does not give.
    writeTextFile(folder / "pillars.x3d",
                  sceneX3d(kPillar + "<Viewpoint position='2 1 12'/><Transform><ProtoInstance name='Pillar' "
                                     "DEF='first'/></Transform><Transform translation='-3 0 0'>"
                                     "<ProtoInstance name='Pillar'><fieldValue name='height' value='3'/>"
                                     "<fieldValue name='color' value='0.2 0.8 0.2'/></ProtoInstance></Transform>"
                                     "<Transform translation='3 -2 0'><ProtoInstance name='Pillar'>"
                                     "<fieldValue name='top'><Box size='0.5 0.5 0.5'/></fieldValue></ProtoInstance>"
                                     "</Transform><Transform translation='0 -3 0'><ProtoInstance name='Pillar' "
                                     "USE='first'/></Transform>"));
    const CommandResult compressed = runCommand(quoted(SYMCOMPRESS_CLI) + " -q " + quoted(folder / "pillars.x3d") +
                                                " -o " + quoted(folder / "out.x3d"));
    INFO(compressed.output);
    REQUIRE(compressed.status == 0);
    checkRendersSame(folder / "pillars.x3d", folder / "out.x3d");
}
