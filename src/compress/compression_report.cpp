// The size report's JSON (symcompress --report): the keys the README lists.
#include "symcompress/compress.hpp"

#include <nlohmann/json.hpp>

namespace symcompress {

std::string CompressionReport::json() const {
    auto orNull = [](const std::optional<std::uintmax_t>& bytes) {
        return bytes ? nlohmann::json(*bytes) : nlohmann::json(nullptr);
    };
    const nlohmann::json report{
        {"input", input.string()},
        {"output", output.string()},
        {"input_bytes", inputBytes},
        {"output_bytes", outputBytes},
        {"ratio", ratio},
        {"plan", plan},
        {"triangles_in", stats.trianglesIn},
        {"triangles_stored", stats.trianglesStored},
        {"line_segments_kept", stats.lineSegmentsKept},
        {"points_kept", stats.pointsKept},
        {"tiles", stats.tiles},
        {"classes", stats.classes},
        {"instanced_classes", stats.instancedClasses},
        {"instances", stats.instances},
        {"symmetric_classes", stats.symmetricClasses},
        {"groups_skipped", stats.groupsSkipped},
        {"attribute_mismatches", stats.attributeMismatches},
        {"not_worth_instancing", stats.notWorthInstancing},
        {"max_deviation", stats.maxDeviation},
        {"tolerance", tolerance},
        {"max_error", maxError},
        {"animation_key_share", animationKeyShare},
        {"skin_weight_share", skinWeightShare},
        {"animation_error", animationError},
        {"seconds",
         {{"read", secondsRead},
          {"tiles", stats.secondsTiles},
          {"classes", stats.secondsClasses},
          {"plan", stats.secondsPlan},
          {"write", secondsWrite}}},
        {"region_classes", stats.regionClasses},
        {"assemblies", stats.assemblies},
        {"assembly_copies", stats.assemblyCopies},
        {"tiles_in_assemblies", stats.tilesInAssemblies},
        {"scene_group", stats.sceneGroup},
        {"tiles_in_scene_symmetry", stats.tilesInSceneSymmetry},
        {"input_instances_kept", stats.inputInstancesKept},
        {"material_variants", stats.materialVariants},
        {"tiles_in_node_frames", stats.tilesInNodeFrames},
        {"node_frames", stats.nodeFrames},
        {"animated_nodes_kept", stats.animatedNodesKept},
        {"cameras_and_lights_kept", stats.camerasAndLightsKept},
        {"bytes_per_instance", bytesPerInstance},
        {"gpu_instancing", {{"batches", gpuInstancing.batches}, {"instances", gpuInstancing.instances}}},
        {"optimizations",
         {{"unread_attributes_dropped", optimizations.unreadAttributesDropped},
          {"flat_normals_dropped", optimizations.flatNormalsDropped},
          {"materials_merged", optimizations.materialsMerged},
          {"textures_merged", optimizations.texturesMerged},
          {"materials_removed", optimizations.materialsRemoved},
          {"textures_removed", optimizations.texturesRemoved},
          {"still_channels_removed", optimizations.stillChannelsRemoved},
          {"animation_keys_dropped", optimizations.animationKeysDropped},
          {"animation_channels_removed", optimizations.animationChannelsRemoved},
          {"primitives_joined_by_base_color", optimizations.primitivesJoinedByColor},
          {"joined_primitives", optimizations.joinedPrimitives}}},
        {"ablation",
         {{"draco_alone", orNull(ablation.dracoAlone)},
          {"instancing", orNull(ablation.instancing)},
          {"instancing_and_regions", orNull(ablation.instancingAndRegions)},
          {"final", outputBytes}}},
        {"warnings", warnings}};
    return report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);  // names from X3D need not be UTF-8
}

}  // namespace symcompress
