// The signing key the codec tests share with node-mavlink (C++: tests/mavlink/peer_support,
// tests/fuzz/fuzz_mavlink_stream.cpp): 32 ASCII bytes, so every side spells it the same.
'use strict'
const KEY = Buffer.from('cover-mavlink-test-key-32-bytes!', 'ascii')
if (KEY.length !== 32) throw new Error('the test key must be 32 bytes')
module.exports = { KEY }
