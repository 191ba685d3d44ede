// Benchmark: tongue-palate collision per frame in JavaScript, on the built scene maxilla and
// 1,000 seeded random tongue poses (every parameter uniform over its range, the jaw included).
// The maxilla is read as the app reads it (bench/support/assets.mjs: GLTFLoader and
// web/src/scene/gltfGeometry.js, the quantised positions dequantised), and checked first against
// the liner's node radii, so that the reference is the surface the tables were built from.
//
// Methods, all timed in this run over the same poses:
//   ours  voxel table + exact liner (web/src/core/collision.js);
//   paper the plain liner of the paper, bilinear radii at the liner step, no exact cells (shown
//         for its error, not as a goal);
//   (a)   exact projection onto the closest triangle, edge or vertex, brute force over every
//         triangle, penetration by the sign of the dot product with the face normal (the paper's
//         slow method; Ericson, Real-Time Collision Detection, 5.1.5);
//   (b)   three-mesh-bvh closestPointToPoint on a prebuilt BVH, same sign test;
//   (c)   three-mesh-bvh raycastFirst from O to each vertex on a prebuilt BVH: the same question
//         the liner answers, exactly, so the fair peer.
// Exactness of ours and of the plain liner is judged against (c) for every vertex of every pose:
// no vertex may stay more than 0.1 mm inside, and no vertex that was outside may move.
// Goals: ours under 0.1 ms median per frame in Node, at least 30 times faster than (c), exact.
//
//   node bench/collision.bench.mjs [poses]     (GLASSHEAD_ASSETS_DIR overrides assets/build)
//   GLASSHEAD_BENCH_QUICK=1: 40 poses, one timed round, (a) on 1 and (b) on 5 of them.
import { DoubleSide, Ray, Triangle, Vector3 } from 'three';
import { MeshBVH } from 'three-mesh-bvh';

import { COLLISION_TOL } from '../web/src/core/constants.js';
import { correctVertices } from '../web/src/core/collision.js';
import { TongueRig } from '../web/src/core/tongue.js';
import { builtCollisionTables, builtJson, builtMesh } from './support/assets.mjs';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const POSES = Number( process.argv[ 2 ] ?? count( 1000, 40 ) );
const SEED = 1998;
const ROUNDS = count( 7, 1 ); // timed passes over all poses for the fast kernels (after one warm-up pass)
const SLOW_POSES = count( 10, 1 ); // (a) is about a second per frame
const BVH_POSES = count( POSES, 5 ); // (b) is about 60 ms per frame
const GOAL_MS = 0.1;
const GOAL_RATIO = 30;

const now = () => Number( process.hrtime.bigint() ) / 1e6;

// --- set-up -------------------------------------------------------------------------------------
const tables = builtCollisionTables();
const rig = new TongueRig( builtJson( 'tongue-rig.json' ) );
// The scene maxilla as the app makes it of the quantised GLB: float32 millimetres.
const geometry = await builtMesh( 'maxilla' );
const bvh = new MeshBVH( geometry );
const n = rig.vertexCount;
const surface = rig.createSurface();
const poses = new Float32Array( POSES * 3 * n );
const draw = random( SEED );
const values = new Float64Array( rig.parameterCount );
for ( let p = 0; p < POSES; p ++ ) {

	for ( let k = 0; k < values.length; k ++ ) values[ k ] = rig.minimum[ k ] + ( rig.maximum[ k ] - rig.minimum[ k ] ) * draw();
	rig.evaluate( values, surface );
	poses.set( surface.positions, p * 3 * n );

}

const [ ox, oy, oz ] = tables.origin;
const work = new Float32Array( 3 * n );
const flags = new Uint8Array( n );
const stats = new Int32Array( 3 );

// --- the methods, each correcting `work` in place -------------------------------------------------
const ours = () => correctVertices( work, n, tables, flags, stats );

// The paper's plain liner: bilinear in the node radii, corrected onto it along the line toward O.
function paperLiner() {

	const { nodeRadius, lon0, lat0, invStep, nlon, nlat, floorY } = tables;
	const row = nlon + 1;
	for ( let v = 0; v < n; v ++ ) {

		const i3 = 3 * v, y = work[ i3 + 1 ];
		if ( y <= floorY ) continue;
		const px = work[ i3 ] - ox, py = y - oy, pz = work[ i3 + 2 ] - oz;
		const rho = Math.sqrt( px * px + py * py );
		const u = ( Math.atan2( px, py ) - lon0 ) * invStep, w = ( Math.atan2( pz, rho ) - lat0 ) * invStep;
		const i = Math.floor( u ), j = Math.floor( w );
		if ( i < 0 || i >= nlon || j < 0 || j >= nlat ) continue;
		const fu = u - i, fw = w - j, c = j * row + i;
		const radius = ( 1 - fw ) * ( ( 1 - fu ) * nodeRadius[ c ] + fu * nodeRadius[ c + 1 ] ) +
			fw * ( ( 1 - fu ) * nodeRadius[ c + row ] + fu * nodeRadius[ c + row + 1 ] );
		const r = Math.sqrt( rho * rho + pz * pz );
		if ( r > radius ) {

			const s = radius / r;
			work[ i3 ] = ox + px * s; work[ i3 + 1 ] = oy + py * s; work[ i3 + 2 ] = oz + pz * s;

		}

	}

}

const position = geometry.attributes.position.array;
const index = geometry.index ? geometry.index.array : Uint32Array.from( { length: position.length / 3 }, ( _, k ) => k );
const triCount = index.length / 3;
const faceNormals = new Float64Array( 3 * triCount );
{

	const t = new Triangle(), nrm = new Vector3();
	for ( let f = 0; f < triCount; f ++ ) {

		t.a.fromArray( position, 3 * index[ 3 * f ] ); t.b.fromArray( position, 3 * index[ 3 * f + 1 ] ); t.c.fromArray( position, 3 * index[ 3 * f + 2 ] );
		t.getNormal( nrm );
		faceNormals[ 3 * f ] = nrm.x; faceNormals[ 3 * f + 1 ] = nrm.y; faceNormals[ 3 * f + 2 ] = nrm.z;

	}

}

// Ericson 5.1.5, closest point on triangle abc to p, into out (3 numbers).
function closestOnTriangle( p, a, b, c, out ) {

	const abx = b[ 0 ] - a[ 0 ], aby = b[ 1 ] - a[ 1 ], abz = b[ 2 ] - a[ 2 ];
	const acx = c[ 0 ] - a[ 0 ], acy = c[ 1 ] - a[ 1 ], acz = c[ 2 ] - a[ 2 ];
	const apx = p[ 0 ] - a[ 0 ], apy = p[ 1 ] - a[ 1 ], apz = p[ 2 ] - a[ 2 ];
	const d1 = abx * apx + aby * apy + abz * apz, d2 = acx * apx + acy * apy + acz * apz;
	const set = ( x, y, z ) => { out[ 0 ] = x; out[ 1 ] = y; out[ 2 ] = z; };
	if ( d1 <= 0 && d2 <= 0 ) return set( a[ 0 ], a[ 1 ], a[ 2 ] );
	const bpx = p[ 0 ] - b[ 0 ], bpy = p[ 1 ] - b[ 1 ], bpz = p[ 2 ] - b[ 2 ];
	const d3 = abx * bpx + aby * bpy + abz * bpz, d4 = acx * bpx + acy * bpy + acz * bpz;
	if ( d3 >= 0 && d4 <= d3 ) return set( b[ 0 ], b[ 1 ], b[ 2 ] );
	const vc = d1 * d4 - d3 * d2;
	if ( vc <= 0 && d1 >= 0 && d3 <= 0 ) {

		const v = d1 / ( d1 - d3 );
		return set( a[ 0 ] + v * abx, a[ 1 ] + v * aby, a[ 2 ] + v * abz );

	}

	const cpx = p[ 0 ] - c[ 0 ], cpy = p[ 1 ] - c[ 1 ], cpz = p[ 2 ] - c[ 2 ];
	const d5 = abx * cpx + aby * cpy + abz * cpz, d6 = acx * cpx + acy * cpy + acz * cpz;
	if ( d6 >= 0 && d5 <= d6 ) return set( c[ 0 ], c[ 1 ], c[ 2 ] );
	const vb = d5 * d2 - d1 * d6;
	if ( vb <= 0 && d2 >= 0 && d6 <= 0 ) {

		const w = d2 / ( d2 - d6 );
		return set( a[ 0 ] + w * acx, a[ 1 ] + w * acy, a[ 2 ] + w * acz );

	}

	const va = d3 * d6 - d5 * d4;
	if ( va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0 ) {

		const w = ( d4 - d3 ) / ( ( d4 - d3 ) + ( d5 - d6 ) );
		return set( b[ 0 ] + w * ( c[ 0 ] - b[ 0 ] ), b[ 1 ] + w * ( c[ 1 ] - b[ 1 ] ), b[ 2 ] + w * ( c[ 2 ] - b[ 2 ] ) );

	}

	const denom = 1 / ( va + vb + vc ), v = vb * denom, w = vc * denom;
	return set( a[ 0 ] + abx * v + acx * w, a[ 1 ] + aby * v + acy * w, a[ 2 ] + abz * v + acz * w );

}

const triVerts = Array.from( { length: triCount }, ( _, f ) => [ 0, 1, 2 ].map( ( k ) => Array.from( position.subarray( 3 * index[ 3 * f + k ], 3 * index[ 3 * f + k ] + 3 ) ) ) );

function projectBruteForce() {

	const p = [ 0, 0, 0 ], q = [ 0, 0, 0 ], best = [ 0, 0, 0 ];
	for ( let v = 0; v < n; v ++ ) {

		p[ 0 ] = work[ 3 * v ]; p[ 1 ] = work[ 3 * v + 1 ]; p[ 2 ] = work[ 3 * v + 2 ];
		let bestD = Infinity, bestF = - 1;
		for ( let f = 0; f < triCount; f ++ ) {

			const [ a, b, c ] = triVerts[ f ];
			closestOnTriangle( p, a, b, c, q );
			const d = ( q[ 0 ] - p[ 0 ] ) ** 2 + ( q[ 1 ] - p[ 1 ] ) ** 2 + ( q[ 2 ] - p[ 2 ] ) ** 2;
			if ( d < bestD ) { bestD = d; bestF = f; best[ 0 ] = q[ 0 ]; best[ 1 ] = q[ 1 ]; best[ 2 ] = q[ 2 ]; }

		}

		const s = ( p[ 0 ] - best[ 0 ] ) * faceNormals[ 3 * bestF ] + ( p[ 1 ] - best[ 1 ] ) * faceNormals[ 3 * bestF + 1 ] + ( p[ 2 ] - best[ 2 ] ) * faceNormals[ 3 * bestF + 2 ];
		if ( s < 0 ) { work[ 3 * v ] = best[ 0 ]; work[ 3 * v + 1 ] = best[ 1 ]; work[ 3 * v + 2 ] = best[ 2 ]; }

	}

}

const point = new Vector3(), hitTarget = { point: new Vector3(), distance: 0, faceIndex: 0 };
function projectBVH() {

	for ( let v = 0; v < n; v ++ ) {

		point.fromArray( work, 3 * v );
		const hit = bvh.closestPointToPoint( point, hitTarget );
		const f = 3 * hit.faceIndex;
		const s = ( point.x - hit.point.x ) * faceNormals[ f ] + ( point.y - hit.point.y ) * faceNormals[ f + 1 ] + ( point.z - hit.point.z ) * faceNormals[ f + 2 ];
		if ( s < 0 ) hit.point.toArray( work, 3 * v );

	}

}

const ray = new Ray( new Vector3( ox, oy, oz ), new Vector3() );
function raycastBVH() {

	for ( let v = 0; v < n; v ++ ) {

		const px = work[ 3 * v ] - ox, py = work[ 3 * v + 1 ] - oy, pz = work[ 3 * v + 2 ] - oz;
		const r = Math.sqrt( px * px + py * py + pz * pz );
		if ( r === 0 ) continue;
		ray.direction.set( px / r, py / r, pz / r );
		const hit = bvh.raycastFirst( ray, DoubleSide, 0, r );
		if ( hit !== null && hit.distance < r ) hit.point.toArray( work, 3 * v );

	}

}

// First-hit radius along the ray from O through each vertex of a pose: the exact reference.
function firstHitRadii( offset, target ) {

	for ( let v = 0; v < n; v ++ ) {

		const px = poses[ offset + 3 * v ] - ox, py = poses[ offset + 3 * v + 1 ] - oy, pz = poses[ offset + 3 * v + 2 ] - oz;
		const r = Math.sqrt( px * px + py * py + pz * pz );
		ray.direction.set( px / r, py / r, pz / r );
		const hit = r > 0 ? bvh.raycastFirst( ray, DoubleSide, 0, Infinity ) : null;
		target[ v ] = hit === null ? Infinity : hit.distance;

	}

}

// The reference mesh must be the one the tables were built from, or the exactness below means
// nothing: the ray through each liner node (every one in a full run, a sample in the quick pass)
// must first hit this maxilla at the node's radius. A mesh read another way (positions rounded,
// a transform lost) fails here by far more than float32 rounding.
function nodeAgreement( stride ) {

	const { nodeRadius, nlon, nlat } = tables;
	const { lon0, lat0, step } = tables.header.liner;
	let worst = 0, disagree = 0, rays = 0;
	for ( let k = 0; k < nodeRadius.length; k += stride ) {

		const i = k % ( nlon + 1 ), j = Math.floor( k / ( nlon + 1 ) );
		if ( j > nlat ) break;
		const lon = lon0 + i * step, lat = lat0 + j * step;
		ray.direction.set( Math.sin( lon ) * Math.cos( lat ), Math.cos( lon ) * Math.cos( lat ), Math.sin( lat ) );
		const hit = bvh.raycastFirst( ray, DoubleSide, 0, Infinity );
		const radius = hit === null ? Infinity : hit.distance;
		rays ++;
		if ( radius === nodeRadius[ k ] ) continue;
		const gap = Math.abs( radius - nodeRadius[ k ] );
		if ( ! ( gap <= COLLISION_TOL.surface ) ) disagree ++;
		if ( Number.isFinite( gap ) ) worst = Math.max( worst, gap );

	}

	return { worst, disagree, rays };

}

// Per pose, the median time over `rounds` timed passes (after one warm-up pass when rounds > 0).
function timeMethod( method, poseCount, rounds ) {

	const times = Array.from( { length: poseCount }, () => [] );
	for ( let round = 0; round <= rounds; round ++ ) {

		for ( let p = 0; p < poseCount; p ++ ) {

			work.set( poses.subarray( p * 3 * n, ( p + 1 ) * 3 * n ) );
			const t0 = now();
			method();
			const t1 = now();
			if ( round > 0 || rounds === 0 ) times[ p ].push( t1 - t0 );

		}

	}

	return times.map( median );

}

// --- exactness against (c) ----------------------------------------------------------------------
function judge( method ) {

	const radii = new Float64Array( n );
	let worst = 0, innocent = 0, missed = 0;
	const corrected = [];
	const screened = [], tested = [];
	for ( let p = 0; p < POSES; p ++ ) {

		const offset = p * 3 * n;
		work.set( poses.subarray( offset, offset + 3 * n ) );
		method();
		if ( method === ours ) { screened.push( stats[ 0 ] ); tested.push( stats[ 1 ] ); }
		firstHitRadii( offset, radii );
		let moved = 0;
		for ( let v = 0; v < n; v ++ ) {

			const i3 = offset + 3 * v;
			const r = Math.hypot( poses[ i3 ] - ox, poses[ i3 + 1 ] - oy, poses[ i3 + 2 ] - oz );
			const after = Math.hypot( work[ 3 * v ] - ox, work[ 3 * v + 1 ] - oy, work[ 3 * v + 2 ] - oz );
			const changed = work[ 3 * v ] !== poses[ i3 ] || work[ 3 * v + 1 ] !== poses[ i3 + 1 ] || work[ 3 * v + 2 ] !== poses[ i3 + 2 ];
			if ( changed ) moved ++;
			if ( changed && r < radii[ v ] - COLLISION_TOL.surface ) innocent ++;
			if ( ! changed && r > radii[ v ] + COLLISION_TOL.surface ) missed ++;
			// The corrected point lies on the same ray, so its depth is measured against the same hit.
			worst = Math.max( worst, after - radii[ v ] );

		}

		corrected.push( moved );

	}

	return { worst, innocent, missed, corrected, screened, tested };

}

// --- run ----------------------------------------------------------------------------------------
console.log( `Collision: ${ POSES } seeded tongue poses (seed ${ SEED }), ${ n } vertices each, jaw included; ` +
	`maxilla ${ triCount } triangles; liner ${ tables.nlon } x ${ tables.nlat } at ${ tables.header.liner.step_deg } deg; ` +
	`voxels ${ Array.from( tables.voxelShape ).join( ' x ' ) }` );

const nodes = nodeAgreement( count( 1, 7 ) );
console.log( `reference maxilla against the liner's node radii: ${ nodes.rays } rays, ${ nodes.disagree } differ by more than ${ COLLISION_TOL.surface } mm, worst finite difference ${ nodes.worst.toExponential( 2 ) } mm` );
const exact = judge( ours );
const plain = judge( paperLiner );
const oursPerPose = timeMethod( ours, POSES, ROUNDS );
const raycastPerPose = timeMethod( raycastBVH, POSES, 1 );
const contact = oursPerPose.filter( ( _, p ) => exact.corrected[ p ] > 0 );
const results = [
	[ 'ours: voxel table + exact liner', median( oursPerPose ), POSES ],
	[ 'ours, frames with contact only', median( contact ), contact.length ],
	[ 'paper: plain bilinear liner', median( timeMethod( paperLiner, POSES, ROUNDS ) ), POSES ],
	[ '(a) closest triangle, brute force', median( timeMethod( projectBruteForce, SLOW_POSES, 0 ) ), SLOW_POSES ],
	[ '(b) three-mesh-bvh closestPointToPoint', median( timeMethod( projectBVH, BVH_POSES, 0 ) ), BVH_POSES ],
	[ '(c) three-mesh-bvh raycastFirst from O', median( raycastPerPose ), POSES ],
	[ '(c), frames with contact only', median( raycastPerPose.filter( ( _, p ) => exact.corrected[ p ] > 0 ) ), contact.length ],
];
const oursMs = results[ 0 ][ 1 ];
console.log( '\nmethod                                     median ms/frame   poses   ours faster by (contact rows: vs ours on contact)' );
for ( const [ name, ms, count ] of results ) {

	const versus = name.includes( 'contact' ) ? results[ 1 ][ 1 ] : oursMs;
	console.log( `${ name.padEnd( 42 ) } ${ ms.toFixed( 4 ).padStart( 14 ) } ${ String( count ).padStart( 7 ) }   ${ name.startsWith( 'ours' ) ? '' : ( ms / versus ).toFixed( 1 ) + 'x' }` );

}

const perPose = ( a ) => `median ${ median( a ) }, mean ${ ( a.reduce( ( x, y ) => x + y, 0 ) / a.length ).toFixed( 1 ) }, max ${ Math.max( ...a ) }`;
console.log( `\nours, per frame: screened ${ median( exact.screened ) }, tested ${ perPose( exact.tested ) }, corrected ${ perPose( exact.corrected ) }` );
console.log( `ours against (c): worst depth after correction ${ exact.worst.toExponential( 2 ) } mm, innocent vertices moved ${ exact.innocent }, vertices left inside ${ exact.missed }` );
console.log( `paper liner against (c): worst depth ${ plain.worst.toFixed( 2 ) } mm, innocent vertices moved ${ plain.innocent }, vertices left inside ${ plain.missed }` );

const ratioC = results[ 5 ][ 1 ] / oursMs;
const ratioContact = results[ 6 ][ 1 ] / results[ 1 ][ 1 ];
const isExact = exact.worst <= COLLISION_TOL.depth && exact.innocent === 0 && exact.missed === 0;
console.log( `\ngoals: median ${ oursMs.toFixed( 4 ) } ms < ${ GOAL_MS } ms: ${ oursMs < GOAL_MS ? 'yes' : 'NO' }; ` +
	`${ ratioC.toFixed( 1 ) }x faster than (c) >= ${ GOAL_RATIO }x: ${ ratioC >= GOAL_RATIO ? 'yes' : 'NO' } ` +
	`(${ ratioContact.toFixed( 1 ) }x on frames with contact); ` +
	`exact: ${ isExact ? 'yes' : 'NO' }` );
check( 'ours is exact against (c)', isExact, `worst depth ${ exact.worst.toExponential( 2 ) } mm, ${ exact.innocent } innocent moved, ${ exact.missed } left inside` );
check( 'the poses touch the palate', contact.length > 0, 'no pose was corrected: nothing was checked' );
