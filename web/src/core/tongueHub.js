// The tongue rig's hub (part of core/tongue.js), the point the page directions and radial moves
// are taken from: step 2, the hub posed with the jaw by its jaw weight, then following its
// parameters (their summed move, posed with the jaw) as far as every turn between neighbouring
// stations keeps hub.keep of its cross product about the unmoved hub (hubShare).

/**
 * The hub tables of a rig definition: its rest position, jaw weight and keep, and the
 * parameters it follows (their indices in `parameterIndex`, a Map name -> index) with their
 * moves (x, y per parameter).
 * @returns {object} the tables, named as the TongueRig's fields that hold them
 */
export function hubTables( hub, parameterIndex ) {

	return {
		hubRest: Float64Array.from( hub.position ),
		hubJawWeight: hub.jaw_weight,
		hubFollowParameter: Int32Array.from( hub.follows, ( f ) => {

			const k = parameterIndex.get( f.parameter );
			if ( k === undefined ) throw new Error( `the hub follows ${f.parameter}, which is not in the parameter table` );
			return k;

		} ),
		hubFollowBy: Float64Array.from( hub.follows.flatMap( ( f ) => f.by ) ),
		hubKeep: hub.keep,
	};

}

/** Step 2, first part: rig.hub is the rest hub moved by the jaw pose rig.pose, by its jaw weight. */
export function poseHub( rig ) {

	rig.hub.set( rig.hubRest );
	const w = rig.hubJawWeight;
	const pose = rig.pose;
	const hx = rig.hub[ 0 ];
	const hy = rig.hub[ 1 ];
	rig.hub[ 0 ] = hx + w * ( pose[ 0 ] * hx + pose[ 1 ] * hy + pose[ 3 ] - hx );
	rig.hub[ 1 ] = hy + w * ( pose[ 4 ] * hx + pose[ 5 ] * hy + pose[ 7 ] - hy );

}

/** Step 2, second part: the hub takes what hubShare allows of its parameters' move. */
export function followWithHub( rig, values ) {

	let fx = 0;
	let fy = 0;
	for ( let m = 0; m < rig.hubFollowParameter.length; m ++ ) {

		const k = rig.hubFollowParameter[ m ];
		fx += ( values[ k ] - rig.neutral[ k ] ) * rig.hubFollowBy[ 2 * m ];
		fy += ( values[ k ] - rig.neutral[ k ] ) * rig.hubFollowBy[ 2 * m + 1 ];

	}

	if ( fx === 0 && fy === 0 ) return;
	// The move posed with the jaw: the hub's pose is affine, so only its linear part acts.
	const w = rig.hubJawWeight;
	const pose = rig.pose;
	const mx = fx + w * ( pose[ 0 ] * fx + pose[ 1 ] * fy - fx );
	const my = fy + w * ( pose[ 4 ] * fx + pose[ 5 ] * fy - fy );
	const share = hubShare( rig, mx, my );
	rig.hub[ 0 ] += share * mx;
	rig.hub[ 1 ] += share * my;

}

/**
 * The share of the move ( mx, my ) that the hub may take: at most 1, and so much that the
 * cross product of every two neighbouring stations seen from the hub keeps hubKeep of its
 * value about the present hub. With a = S_i - H and b = S_i+1 - H, the cross product from
 * H + t * move is a x b - t ( a - b ) x move: linear in t, so its bound is exact.
 */
export function hubShare( rig, mx, my ) {

	const hx = rig.hub[ 0 ];
	const hy = rig.hub[ 1 ];
	const stationXY = rig.stationXY;
	const count = rig.stationCount;
	let bound = Infinity;
	for ( let i = 0; i < count; i ++ ) {

		const j = ( i + 1 ) % count;
		const ax = stationXY[ 2 * i ] - hx;
		const ay = stationXY[ 2 * i + 1 ] - hy;
		const bx = stationXY[ 2 * j ] - hx;
		const by = stationXY[ 2 * j + 1 ] - hy;
		const cross = ax * by - ay * bx;
		const loss = ( ax - bx ) * my - ( ay - by ) * mx;
		if ( loss > 0 && cross > 0 ) bound = Math.min( bound, cross / loss );

	}

	return Math.min( 1, ( 1 - rig.hubKeep ) * bound );

}
