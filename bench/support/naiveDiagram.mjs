// Shared by the diagram and frame benchmarks: the straightforward versions of the diagram's
// section and constriction, as a first version would write them, for baselines in the same run.
import { chainSegments } from '../../web/src/core/sectionPolygon.js';

/**
 * The naive section of a DiagramSection's moving parts: each cut triangle by triangle into new
 * arrays (rigid parts' vertices posed first) and chained with a Map of point keys
 * (core/sectionPolygon.js chainSegments). Returns the chains per part.
 */
export function naiveSection( diagram ) {

	const out = [];
	for ( const mesh of diagram.meshes ) {

		if ( mesh.motion === 'still' ) continue;
		const source = mesh.scenePart.geometry.attributes.position.array;
		const pose = diagram.poseOf( mesh );
		const positions = pose ? posed( source, pose ) : source;
		const index = mesh.section.index;
		const segments = [];
		for ( let t = 0; t < index.length; t += 3 ) {

			const tri = [ index[ t ], index[ t + 1 ], index[ t + 2 ] ].map( ( v ) => [ positions[ 3 * v ], positions[ 3 * v + 1 ], positions[ 3 * v + 2 ] ] );
			const cut = [];
			for ( let e = 0; e < 3; e ++ ) {

				const a = tri[ e ], b = tri[ ( e + 1 ) % 3 ];
				if ( ( a[ 2 ] >= 0 ) === ( b[ 2 ] >= 0 ) ) continue;
				const s = a[ 2 ] / ( a[ 2 ] - b[ 2 ] );
				cut.push( a[ 0 ] + ( b[ 0 ] - a[ 0 ] ) * s, a[ 1 ] + ( b[ 1 ] - a[ 1 ] ) * s, 0 );

			}

			if ( cut.length === 6 ) segments.push( ...cut );

		}

		out.push( chainSegments( Float64Array.from( segments ), segments.length / 6 ) );

	}

	return out;

}

function posed( source, pose ) {

	const out = new Float32Array( source.length );
	for ( let v = 0; v < source.length; v += 3 ) {

		const x = source[ v ], y = source[ v + 1 ], z = source[ v + 2 ];
		out[ v ] = pose[ 0 ] * x + pose[ 1 ] * y + pose[ 2 ] * z + pose[ 3 ];
		out[ v + 1 ] = pose[ 4 ] * x + pose[ 5 ] * y + pose[ 6 ] * z + pose[ 7 ];
		out[ v + 2 ] = pose[ 8 ] * x + pose[ 9 ] * y + pose[ 10 ] * z + pose[ 11 ];

	}

	return out;

}

/** Every floor point of a cut DiagramSection against every roof segment and back: the width (mm). */
export function bruteConstriction( diagram ) {

	let best = Infinity;
	const pass = ( from, to ) => {

		for ( const a of from ) for ( let k = 0; k < a.pointCount; k ++ ) {

			const x = a.points[ 2 * k ], y = a.points[ 2 * k + 1 ];
			for ( const b of to ) for ( let c = 0; c < b.chainCount; c ++ ) {

				const first = b.starts[ c ], n = b.starts[ c + 1 ] - first;
				for ( let s = 0; s < ( b.closed[ c ] ? n : n - 1 ); s ++ ) {

					const i = first + s, j = first + ( s + 1 ) % n;
					const ax = b.points[ 2 * i ], ay = b.points[ 2 * i + 1 ];
					const dx = b.points[ 2 * j ] - ax, dy = b.points[ 2 * j + 1 ] - ay;
					const l2 = dx * dx + dy * dy;
					const t = l2 > 0 ? Math.min( 1, Math.max( 0, ( ( x - ax ) * dx + ( y - ay ) * dy ) / l2 ) ) : 0;
					best = Math.min( best, ( ax + t * dx - x ) ** 2 + ( ay + t * dy - y ) ** 2 );

				}

			}

		}

	};
	pass( diagram.floor, diagram.roof );
	pass( diagram.roof, diagram.floor );
	return Math.sqrt( best );

}
