#!/usr/bin/env node
// Reads frames COVER's encoder wrote, with node-mavlink's splitter and parser, and prints
// what it decoded (tests/mavlink/peer_test.cpp: MavlinkPeer.NodeReadsOurFrames).
//
//   node read_frames.js --frames IN.bin
//
// Prints one JSON object on stdout: {frames: [{message, id, version, signed,
// signature_valid (against test_key.js; null when unsigned), seq, sysid, compid,
// payload_length, fields}], crc_errors, unknown}. Field names as in codec.js. Exit 0, or 1
// with the reason on stderr.
'use strict'
const fs = require('fs')
const { Readable } = require('stream')
const { MavLinkPacketSplitter, MavLinkPacketParser } = require('node-mavlink')
const { BY_ID, toJson } = require('./codec')
const { KEY } = require('./test_key')

function arg(name) {
  const i = process.argv.indexOf(name)
  if (i < 0 || i + 1 >= process.argv.length) {
    process.stderr.write(`read_frames: ${name} FILE is required\n`)
    process.exit(1)
  }
  return process.argv[i + 1]
}

function describe(packet) {
  const known = BY_ID[packet.header.msgid]
  const signed = packet.signature !== null
  return {
    message: known ? known.name : null,
    id: packet.header.msgid,
    version: packet.header.magic === 0xfd ? 2 : 1,
    signed,
    signature_valid: signed ? packet.signature.matches(KEY) : null,
    seq: packet.header.seq,
    sysid: packet.header.sysid,
    compid: packet.header.compid,
    payload_length: packet.header.payloadLength,
    fields: known ? toJson(packet.protocol.data(packet.payload, known.clazz)) : null,
  }
}

function main() {
  const bytes = fs.readFileSync(arg('--frames'))
  const splitter = new MavLinkPacketSplitter()
  const frames = []
  Readable.from([bytes])
    .pipe(splitter)
    .pipe(new MavLinkPacketParser())
    .on('data', (packet) => frames.push(describe(packet)))
    .on('error', (error) => {
      process.stderr.write(`read_frames: ${error.message}\n`)
      process.exit(1)
    })
    .on('end', () => {
      process.stdout.write(JSON.stringify({ frames, crc_errors: splitter.invalidPackages,
                                            unknown: splitter.unknownPackagesCount }) + '\n')
    })
}

main()
