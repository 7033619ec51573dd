// meshoptimizer's own encoder and decoder (its npm package in ../shared/bench/node), as the ground truth of
// test_meshopt_codec.cpp: encodes COUNT elements of STRIDE bytes at vertex codec version 1 and decodes the stream
// again with FILTER applied.
// Usage: node meshopt_reference.mjs --modules NODE_MODULES --in RAW --count N --stride S [--filter COLOR --bits K]
//        --stream OUT_STREAM --decoded OUT_DECODED
// With --filter COLOR, RAW holds N RGBA float32 colours, filtered to K bits before encoding.
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const options = { modules: null, in: null, count: null, stride: null, filter: 'NONE', bits: '8', level: '2', stream: null, decoded: null };
const args = process.argv.slice(2);
for (let i = 0; i + 1 < args.length; i += 2) options[args[i].replace(/^--/, '')] = args[i + 1];
if (!options.modules || !options.in || !options.stream || !options.decoded) {
    console.error('usage: node meshopt_reference.mjs --modules DIR --in RAW --count N --stride S [--filter COLOR --bits K] --stream OUT --decoded OUT');
    process.exit(2);
}
const load = (file) => import(pathToFileURL(path.join(options.modules, 'meshoptimizer', file)).href);
const { MeshoptEncoder } = await load('meshopt_encoder.js');
const { MeshoptDecoder } = await load('meshopt_decoder.mjs');
await MeshoptEncoder.ready;
await MeshoptDecoder.ready;

const count = Number(options.count), stride = Number(options.stride);
const raw = new Uint8Array(fs.readFileSync(options.in));
const source = options.filter === 'COLOR'
    ? MeshoptEncoder.encodeFilterColor(new Float32Array(raw.buffer, raw.byteOffset, count * 4), count, stride, Number(options.bits))
    : raw;
const stream = MeshoptEncoder.encodeVertexBufferLevel(source, count, stride, Number(options.level), 1);
const decoded = new Uint8Array(count * stride);
MeshoptDecoder.decodeGltfBuffer(decoded, count, stride, stream, 'ATTRIBUTES', options.filter);
fs.writeFileSync(options.stream, stream);
fs.writeFileSync(options.decoded, decoded);
