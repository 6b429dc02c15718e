// Reads a `slamctl record` file with @mcap/core, the MCAP library Foxglove itself uses: the indexed
// reader opens it from its summary (no chunks: the file is unchunked), the statistics count every
// Message record, each expected topic has a cdr channel with an omgidl schema of that name, and the
// streaming reader walks every record to the end with CRCs checked.
// Usage: node mcap_reader_test.mjs FILE TOPIC=SCHEMA_NAME...
// Exit 0 when everything held, 1 with one line saying what did not.
import { readFileSync } from "node:fs";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";

function fail(message) {
  console.error(`mcap_reader_test: FAIL: ${message}`);
  process.exit(1);
}

const [file, ...expectations] = process.argv.slice(2);
if (!file || expectations.length === 0) fail("usage: mcap_reader_test.mjs FILE TOPIC=SCHEMA_NAME...");
const bytes = new Uint8Array(readFileSync(file));

const readable = {
  size: async () => BigInt(bytes.byteLength),
  read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
};
let indexed;
try {
  indexed = await McapIndexedReader.Initialize({ readable });
} catch (e) {
  fail(`McapIndexedReader.Initialize: ${e.message}`);
}
if (indexed.chunkIndexes.length !== 0) fail(`${indexed.chunkIndexes.length} chunk indexes in an unchunked file`);
if (!indexed.statistics) fail("no Statistics record in the summary");

for (const expectation of expectations) {
  const [topic, schemaName] = expectation.split("=");
  const channel = [...indexed.channelsById.values()].find((c) => c.topic === topic);
  if (!channel) fail(`no channel for ${topic}`);
  if (channel.messageEncoding !== "cdr") fail(`${topic}: message encoding ${channel.messageEncoding}`);
  const schema = indexed.schemasById.get(channel.schemaId);
  if (!schema) fail(`${topic}: no schema ${channel.schemaId}`);
  if (schema.encoding !== "omgidl") fail(`${topic}: schema encoding ${schema.encoding}`);
  if (schema.name !== schemaName) fail(`${topic}: schema ${schema.name}, expected ${schemaName}`);
  const local = schemaName.slice(schemaName.lastIndexOf(":") + 1);
  if (!new TextDecoder().decode(schema.data).includes(`struct ${local}`))
    fail(`${topic}: the schema text does not define ${local}`);
}

// Every record, in order, with the data and summary CRCs checked.
const stream = new McapStreamReader({ validateCrcs: true });
stream.append(bytes);
let messages = 0n;
for (;;) {
  let record;
  try {
    record = stream.nextRecord();
  } catch (e) {
    fail(`McapStreamReader: ${e.message}`);
  }
  if (!record) break;
  if (record.type === "Message") messages += 1n;
}
if (!stream.done()) fail("McapStreamReader did not reach the end of the file");
if (indexed.statistics.messageCount !== messages)
  fail(`statistics say ${indexed.statistics.messageCount} messages, the file has ${messages}`);
console.log(`ok: ${messages} messages on ${indexed.channelsById.size} channels`);
