// The label layer's pure parts: which landmarks it shows, where each label goes on the screen so
// that labels overlap neither each other nor the panels over the view (the EPG card, the side
// panel), and which part a pointer over a mesh names. No DOM, no three.js:
// tested in Node (tests/js/labelPlacement.test.js).

/** Format version of GET /anatomy/landmarks this app reads (LANDMARKS_FORMAT_VERSION). */
import { LANDMARKS_FORMAT_VERSION } from '../../core/constants.js';

/** Scene meshes with no landmark of their own, named when pointed at. */
export const MESH_NAMES = Object.freeze( { mandible: 'jaw', cranium: 'skull', hyoid: 'hyoid bone', vertebrae: 'spine' } );

/** Radii (CSS px) at which a label is tried around its landmark, nearest first. */
const RADII = Object.freeze( [ 34, 56, 82, 112, 150, 196, 250, 310 ] );
/** Angles (degrees) tried on each side of the preferred direction. */
const TURNS = Object.freeze( [ 0, 25, - 25, 50, - 50, 80, - 80, 115, - 115, 150, - 150, 180 ] );
/** Space kept between two labels, CSS px. */
const MARGIN = 4;
/** Cost of covering a panel, per px² overlapped, against 1 for covering another label: a label
 * goes over a panel only when no spot is free of it. */
const OBSTACLE_WEIGHT = 1000;

/** Check a landmarks document (GET /anatomy/landmarks); returns its shown entries. */
export function labelEntries( document ) {

	if ( ! document || document.format_version !== LANDMARKS_FORMAT_VERSION ) {

		throw new Error( `landmarks format_version ${ document?.format_version } is not ${ LANDMARKS_FORMAT_VERSION }: rebuild the assets` );

	}

	return document.landmarks
		.filter( ( entry ) => entry.kind === 'part' || entry.kind === 'place' )
		.map( ( entry ) => ( { name: entry.name, label: entry.label, kind: entry.kind, position: entry.position, meshes: entry.meshes ?? [], order: entry.order ?? null } ) );

}

function overlaps( a, b ) {

	return a.x < b.x + b.w + MARGIN && b.x < a.x + a.w + MARGIN && a.y < b.y + b.h + MARGIN && b.y < a.y + a.h + MARGIN;

}

function overlapArea( a, b ) {

	const w = Math.min( a.x + a.w, b.x + b.w ) - Math.max( a.x, b.x ) + MARGIN;
	const h = Math.min( a.y + a.h, b.y + b.h ) - Math.max( a.y, b.y ) + MARGIN;
	return w > 0 && h > 0 ? w * h : 0;

}

/**
 * Place labels around their anchors without overlap where the screen allows it (greedy, in the
 * given order: earlier labels get the nearer spots).
 * anchors: [{ x, y, w, h, angle }] the landmark on the screen (CSS px), the label's size and its
 * preferred direction (radians, screen: +x right, +y down). bounds: { width, height }.
 * obstacles: [{ x, y, w, h }] screen rectangles no label may cover (panels over the view).
 * Returns [{ x, y, w, h, overlapping }] the top-left corner of each label's box; overlapping:
 * it covers another label or an obstacle (no free spot was found).
 */
export function placeLabels( anchors, bounds, obstacles = [] ) {

	const placed = [];
	const dots = anchors.map( ( a ) => ( { x: a.x - 5, y: a.y - 5, w: 10, h: 10 } ) );
	for ( let i = 0; i < anchors.length; i ++ ) {

		const a = anchors[ i ];
		let best = null;
		let bestCost = Infinity;
		search: for ( const radius of RADII ) {

			for ( const turn of TURNS ) {

				const angle = a.angle + turn * Math.PI / 180;
				const cx = a.x + radius * Math.cos( angle );
				const cy = a.y + radius * Math.sin( angle );
				// The box's nearest side faces the anchor.
				const box = { x: cx - a.w / 2 + Math.cos( angle ) * a.w / 2, y: cy - a.h / 2, w: a.w, h: a.h };
				box.x = Math.min( Math.max( box.x, 0 ), Math.max( 0, bounds.width - a.w ) );
				box.y = Math.min( Math.max( box.y, 0 ), Math.max( 0, bounds.height - a.h ) );
				let cost = 0;
				for ( const obstacle of obstacles ) cost += OBSTACLE_WEIGHT * overlapArea( box, obstacle );
				for ( const other of placed ) cost += overlapArea( box, other );
				for ( let k = 0; k < dots.length; k ++ ) if ( k !== i ) cost += 0.25 * overlapArea( box, dots[ k ] );
				if ( cost === 0 ) {

					best = box;
					break search;

				}

				if ( cost < bestCost ) {

					best = box;
					bestCost = cost;

				}

			}

		}

		placed.push( { ...best, overlapping: placed.some( ( other ) => overlaps( best, other ) ) || obstacles.some( ( other ) => overlaps( best, other ) ) } );

	}

	return placed;

}

/**
 * The preferred direction of each label (radians): places of articulation above the roof of the
 * mouth (straight up on the screen), parts away from the middle of the parts' anchors.
 * entries: [{ kind }]; points: [{ x, y }] their anchors on the screen.
 */
export function preferredAngles( entries, points ) {

	const parts = points.filter( ( _, i ) => entries[ i ].kind === 'part' );
	const cx = parts.reduce( ( sum, p ) => sum + p.x, 0 ) / Math.max( 1, parts.length );
	const cy = parts.reduce( ( sum, p ) => sum + p.y, 0 ) / Math.max( 1, parts.length );
	return points.map( ( p, i ) => {

		if ( entries[ i ].kind === 'place' ) return - Math.PI / 2;
		const dx = p.x - cx, dy = p.y - cy;
		return dx === 0 && dy === 0 ? Math.PI / 2 : Math.atan2( dy, dx );

	} );

}

/**
 * The name of the part at a point of a mesh: the nearest part landmark among those that name
 * that mesh (on the tongue: tip, blade, front, back or root), teeth where `isTooth` says so.
 * meshName: the scene mesh hit; point: [x, y, z] mm; entries: labelEntries(); isTooth: boolean
 * or null. Returns { name, label } or null.
 */
export function partAt( meshName, point, entries, { isTooth = null } = {} ) {

	if ( isTooth === true ) {

		const teeth = entries.find( ( entry ) => entry.name === 'teeth' );
		if ( teeth ) return { name: teeth.name, label: teeth.label };

	}

	let best = null;
	let bestDistance = Infinity;
	for ( const entry of entries ) {

		if ( entry.kind !== 'part' || ! entry.meshes.includes( meshName ) ) continue;
		if ( isTooth === false && entry.name === 'teeth' ) continue;
		const d = Math.hypot( entry.position[ 0 ] - point[ 0 ], entry.position[ 1 ] - point[ 1 ], entry.position[ 2 ] - point[ 2 ] );
		if ( d < bestDistance ) {

			best = entry;
			bestDistance = d;

		}

	}

	if ( best ) return { name: best.name, label: best.label };
	if ( meshName in MESH_NAMES ) return { name: meshName, label: MESH_NAMES[ meshName ] };
	return null;

}
